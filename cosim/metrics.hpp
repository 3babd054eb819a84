// Accuracy of a quantized image against the float truth, in output LSBs.
//
// The truth's channel x in [0, 1] is worth x * (2^bits - 1) LSBs; a quantized
// channel q differs from it by |q - x (2^bits - 1)|. Figures are over the three
// colour channels (premultiplied, the volume alone).
#pragma once

#include <cstddef>

#include "refmodel/render/image.hpp"
#include "refmodel/render/quant_image.hpp"

namespace voxcast::cosim {

struct Accuracy {
  double max_abs_err_lsb = 0.0;
  double mean_abs_err_lsb = 0.0;
  double rms_err_lsb = 0.0;
  double psnr_db = 0.0;          // 20 log10(peak / rms); +inf when rms = 0
  double pct_within_1lsb = 0.0;  // pixels whose three channels are all within 1 LSB
  int worst_x = -1, worst_y = -1;
};

Accuracy measure_accuracy(const ref::QuantImage& test, const ref::Image& truth);

// Heat map of the largest channel error per pixel: black = 0, through red and
// yellow to white at `full_scale_lsb` LSBs and above.
ref::Image error_heat_map(const ref::QuantImage& test, const ref::Image& truth,
                          double full_scale_lsb);

}  // namespace voxcast::cosim
