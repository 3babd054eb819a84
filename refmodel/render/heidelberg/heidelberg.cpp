#include "refmodel/render/heidelberg/heidelberg.hpp"

#include <optional>

#include "refmodel/parallel.hpp"
#include "refmodel/render/heidelberg/rotator.hpp"
#include "refmodel/render/heidelberg/slice_model.hpp"

namespace voxcast::ref::heidelberg {

std::vector<double> eye_offsets(const HeidelbergDesc& h) {
  if (h.stereo_deg <= 0.0) return {0.0};
  return {-0.5 * h.stereo_deg, 0.5 * h.stereo_deg};
}

Image render(const Scene& scene, const Volume& volume, double eye_offset_deg, int threads) {
  const HeidelbergDesc& h = scene.heidelberg;
  const ViewDims dims = view_dims(scene, volume);
  const ViewTransform vt = make_view_transform(h, volume, dims, eye_offset_deg);
  const DensityVolume dv = make_density_volume(scene, volume);
  const SliceParams sp = slice_params(h);
  const bool three_d = h.gradient == HeidelbergGradient::Sobel3D;
  Image img(dims.W, dims.H);
  // Each plane k is one image line (row H - 1 - k: z up).
  parallel_for(
      dims.H,
      [&](int k) {
        const Plane mid = rotate_plane(dv, vt, h.interpolation, h.gaussian_sigma, k);
        std::optional<Plane> below, above;
        if (three_d) {
          below = rotate_plane(dv, vt, h.interpolation, h.gaussian_sigma, k - 1);
          above = rotate_plane(dv, vt, h.interpolation, h.gaussian_sigma, k + 1);
        }
        const PlaneGradients g = sobel(mid, below ? &*below : nullptr, above ? &*above : nullptr);
        const Line line = trace_slice(sp, dims.W, dims.D, mid.v.data(), g.gx.v.data(),
                                      g.gy.v.data(), three_d ? g.gz.v.data() : nullptr);
        for (int x = 0; x < dims.W; ++x) {
          const double v = line.value[static_cast<std::size_t>(x)];
          img.at(x, dims.H - 1 - k) = line.background[static_cast<std::size_t>(x)]
                                          ? glm::dvec4(0.0)
                                          : glm::dvec4(v, v, v, 1.0);
        }
      },
      threads);
  return img;
}

}  // namespace voxcast::ref::heidelberg
