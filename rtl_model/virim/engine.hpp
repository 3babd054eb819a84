// The rtl engine for VIRIM (render.algorithm = "heidelberg"): the cycle model
// of the rotator modules and their DSPs rendering one frame (docs/virim-rtl.md).
// Inputs are the host set-up and parity memory the hls and bit-true engines
// read; every value is computed by the hls/virim/ kernels, so the image is the
// hls engine's bit for bit by construction (and checked by the tests and by
// `voxcast cosim`). The modules are independent (each has its own copy of the
// data cube, rotator, bus and DSPs) and run on up to `threads` host threads;
// cycles and pixels do not depend on the thread count.
#pragma once

#include <string>

#include "refmodel/bittrue/heidelberg.hpp"
#include "refmodel/render/quant_image.hpp"
#include "rtl_model/virim/config.hpp"
#include "rtl_model/virim/stats.hpp"

namespace voxcast::rtl::virim {

struct VirimRtlResult {
  ref::QuantImage image;  // as hls_render_heidelberg delivers it
  VirimRtlStats stats;
};

// Throws voxcast::Error for an invalid configuration, a profile the hls
// kernels are not compiled for, a buffer too small for a line (the rotator
// would deadlock) or data left in a FIFO at the end of the frame.
VirimRtlResult virim_rtl_render(const bittrue::VirimSetup& setup, const bittrue::VirimMemory& memory,
                                const VirimRtlConfig& config = {}, int threads = 1);

}  // namespace voxcast::rtl::virim
