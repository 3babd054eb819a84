// VIRIM's pipeline in double precision: LUT -> rotator -> per-plane
// perspective -> the Heidelberg Raytracing Model slice by slice
// (docs/heidelberg.md). The float reference for `render.algorithm = "heidelberg"`.
#pragma once

#include "refmodel/render/image.hpp"
#include "refmodel/scene/scene.hpp"
#include "refmodel/volume/volume.hpp"

namespace voxcast::ref::heidelberg {

// The stereo eyes (§6): offsets about the view's z axis in degrees; one eye
// (0) when heidelberg.stereo_deg = 0, else −stereo/2 (left) and +stereo/2.
std::vector<double> eye_offsets(const HeidelbergDesc& h);

// One image: W x H gray (r = g = b), alpha 1 on the data and 0 where the
// background was identified (render.background shows there).
Image render(const Scene& scene, const Volume& volume, double eye_offset_deg, int threads = 0);

}  // namespace voxcast::ref::heidelberg
