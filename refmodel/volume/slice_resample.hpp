// Resampling a stack of parallel slices onto a regular grid: what the DICOM
// loader does with a gantry-tilted series (each slice shifted in its own plane
// from the one before) or unevenly spaced slices (a missing slice), as
// dcm2niix and scanner consoles do (docs/volumes.md, "DICOM series", rule 7).
//
// Coordinates are those of the slices' own frame (ImageOrientationPatient):
// u along a row (the row direction cosines), v down a column (the column
// direction cosines), w along the slice normal (row x column), all in mm. A
// slice's pixel (i, j) lies at (u + i * spacing_x, v + j * spacing_y, w).
// No GDCM here: the loader hands over decoded stored values.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace voxcast::ref {

struct StackSlice {
  std::string name;                       // file name, for messages
  const std::uint16_t* values = nullptr;  // columns x rows stored values, x fastest
  double u = 0.0, v = 0.0, w = 0.0;       // ImagePositionPatient in the slice frame, mm
};

struct StackLayout {
  int columns = 0, rows = 0;
  double spacing_x = 1.0, spacing_y = 1.0;  // mm between columns, between rows
};

// The regular grid a stack is resampled onto, and what made it necessary.
struct RegularGrid {
  int slices = 0;                       // planes along w
  double spacing_z = 0.0;               // mm between planes: the median gap between slices
  double u0 = 0.0, v0 = 0.0, w0 = 0.0;  // where voxel (0, 0, 0) lies
  double shear_u = 0.0, shear_v = 0.0;  // in-plane shift per mm along w (the tilt)
  double tilt_deg = 0.0;                // atan(|shear|): the gantry tilt
  int uneven_gaps = 0;                  // gaps more than 1% from the median
};

inline constexpr double kMaxTiltDeg = 45.0;

// Plans the grid for `slices` sorted by w, at least two, no two closer than
// the loader's duplicate distance. Throws voxcast::Error "`where`: reason" for a
// degenerate series: a tilt above kMaxTiltDeg, slice positions off the line of
// one tilt by more than a pixel, or a grid above the loaders' voxel limit.
RegularGrid plan_regular_grid(const std::vector<StackSlice>& slices, const StackLayout& layout,
                              const std::string& where);

// The stored values on `grid` (columns x rows x grid.slices, x fastest):
// bilinear in each slice's plane at the voxel's (u, v), linear along w between
// the two slices around the plane, rounded half up. Points outside a slice
// take `fill` (the series' lowest stored value). A plane beyond the last slice
// (at most half a gap) takes the last slice.
std::vector<std::uint16_t> resample_stack(const std::vector<StackSlice>& slices,
                                          const StackLayout& layout, const RegularGrid& grid,
                                          std::uint16_t fill);

}  // namespace voxcast::ref
