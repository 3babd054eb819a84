// Resampling a slice stack onto a regular grid (slice_resample.hpp).
#include "refmodel/volume/slice_resample.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <numbers>

#include "refmodel/error.hpp"
#include "refmodel/volume/loaders.hpp"

namespace voxcast::ref {
namespace {

constexpr double kUnevenTolerance = 0.01;  // as the loader: relative deviation from the median gap
constexpr double kSnapPixels = 1e-6;       // an in-plane offset smaller than this is none

std::string format_number(double v, const char* format = "%.6g") {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

// One slice's in-plane offset on the grid, split into whole pixels and a
// fraction in [0, 1): the grid's pixel i lies at the slice's i + whole + frac.
struct Offset {
  long whole = 0;
  double frac = 0.0;
};

Offset offset_of(double pixels) {
  if (std::abs(pixels - std::round(pixels)) < kSnapPixels) pixels = std::round(pixels);
  const double whole = std::floor(pixels);
  return {static_cast<long>(whole), pixels - whole};
}

// Bilinear sampling of one slice with a constant offset; pixels outside the
// slice are `fill`.
class ShiftedSlice {
 public:
  ShiftedSlice(const StackSlice& s, const StackLayout& l, const RegularGrid& g, double fill)
      : values_(s.values),
        columns_(l.columns),
        rows_(l.rows),
        fill_(fill),
        ox_(offset_of((g.u0 - s.u) / l.spacing_x)),
        oy_(offset_of((g.v0 - s.v) / l.spacing_y)) {}

  double at(int i, int j) const {
    const long x = i + ox_.whole, y = j + oy_.whole;
    const double a = pixel(x, y);
    if (ox_.frac == 0.0 && oy_.frac == 0.0) return a;
    const double b = pixel(x + 1, y), c = pixel(x, y + 1), d = pixel(x + 1, y + 1);
    const double top = a + ox_.frac * (b - a), bottom = c + ox_.frac * (d - c);
    return top + oy_.frac * (bottom - top);
  }

 private:
  double pixel(long x, long y) const {
    if (x < 0 || y < 0 || x >= columns_ || y >= rows_) return fill_;
    return values_[static_cast<std::size_t>(y) * static_cast<std::size_t>(columns_) +
                   static_cast<std::size_t>(x)];
  }
  const std::uint16_t* values_;
  long columns_, rows_;
  double fill_;
  Offset ox_, oy_;
};

}  // namespace

RegularGrid plan_regular_grid(const std::vector<StackSlice>& slices, const StackLayout& layout,
                              const std::string& where) {
  const std::size_t n = slices.size();
  if (n < 2)
    throw Error(where + ": a stack of " + std::to_string(n) + " slice cannot be resampled");
  RegularGrid g;

  // Spacing: the median gap along the normal (one missing slice does not move it).
  std::vector<double> gaps(n - 1);
  for (std::size_t k = 0; k + 1 < n; ++k) gaps[k] = slices[k + 1].w - slices[k].w;
  std::vector<double> sorted = gaps;
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2),
                   sorted.end());
  g.spacing_z = sorted[sorted.size() / 2];
  for (double gap : gaps)
    g.uneven_gaps += std::abs(gap - g.spacing_z) > kUnevenTolerance * g.spacing_z;

  // Tilt: the in-plane shift per mm along the normal, from the first slice to the last.
  const StackSlice& first = slices.front();
  const StackSlice& last = slices.back();
  const double extent = last.w - first.w;
  g.shear_u = (last.u - first.u) / extent;
  g.shear_v = (last.v - first.v) / extent;
  g.tilt_deg = std::atan(std::hypot(g.shear_u, g.shear_v)) * 180.0 / std::numbers::pi;
  if (!(g.tilt_deg <= kMaxTiltDeg))
    throw Error(where + ": the slice positions lean " + format_number(g.tilt_deg, "%.1f") +
                " deg from ImageOrientationPatient's normal (" + first.name + " to " + last.name +
                "), more than " + format_number(kMaxTiltDeg) +
                " deg: a degenerate series, not a gantry tilt that can be resampled");
  // Every slice on the line of that one tilt, within a pixel.
  for (const StackSlice& s : slices) {
    const double du = (s.u - first.u - g.shear_u * (s.w - first.w)) / layout.spacing_x;
    const double dv = (s.v - first.v - g.shear_v * (s.w - first.w)) / layout.spacing_y;
    if (std::hypot(du, dv) > 1.0)
      throw Error(where + ": " + s.name + " is offset " + format_number(std::hypot(du, dv), "%.1f") +
                  " pixels sideways from the line of slice positions through " + first.name +
                  " and " + last.name + " (not one gantry tilt: cannot resample)");
  }

  // Extent: from the first slice, round(extent / spacing) gaps; in-plane, the
  // grid of the slice half-way up the stack, so both ends lose the same margin.
  const double planes = std::round(extent / g.spacing_z) + 1.0;
  const double voxels = planes * layout.columns * layout.rows;
  if (!(voxels <= static_cast<double>(kMaxLoadVoxels)))
    throw Error(where + ": resampling onto " + format_number(g.spacing_z) + " mm slices needs " +
                format_number(planes, "%.0f") + " slices, more than the limit of 2^31 voxels");
  g.slices = static_cast<int>(planes);
  g.w0 = first.w;
  g.u0 = first.u + g.shear_u * extent / 2.0;
  g.v0 = first.v + g.shear_v * extent / 2.0;
  return g;
}

std::vector<std::uint16_t> resample_stack(const std::vector<StackSlice>& slices,
                                          const StackLayout& layout, const RegularGrid& grid,
                                          std::uint16_t fill) {
  std::vector<ShiftedSlice> shifted;
  shifted.reserve(slices.size());
  for (const StackSlice& s : slices) shifted.emplace_back(s, layout, grid, fill);
  const std::size_t per_plane =
      static_cast<std::size_t>(layout.columns) * static_cast<std::size_t>(layout.rows);
  std::vector<std::uint16_t> out(per_plane * static_cast<std::size_t>(grid.slices));
  std::size_t k = 0;  // slices[k].w <= w < slices[k + 1].w
  for (int m = 0; m < grid.slices; ++m) {
    const double w = std::min(grid.w0 + m * grid.spacing_z, slices.back().w);
    while (k + 2 < slices.size() && slices[k + 1].w <= w) ++k;
    const double t = std::clamp((w - slices[k].w) / (slices[k + 1].w - slices[k].w), 0.0, 1.0);
    std::uint16_t* plane = out.data() + per_plane * static_cast<std::size_t>(m);
    for (int j = 0; j < layout.rows; ++j)
      for (int i = 0; i < layout.columns; ++i) {
        const double a = shifted[k].at(i, j);
        const double value = t == 0.0 ? a : a + t * (shifted[k + 1].at(i, j) - a);
        plane[static_cast<std::size_t>(j) * static_cast<std::size_t>(layout.columns) +
              static_cast<std::size_t>(i)] = static_cast<std::uint16_t>(std::floor(value + 0.5));
      }
  }
  return out;
}

}  // namespace voxcast::ref
