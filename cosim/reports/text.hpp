// Numbers as the Markdown and HTML reports print them.
#pragma once

#include <cmath>
#include <cstdio>
#include <string>

namespace voxcast::cosim {

// `v` with `decimals` digits after the point; "inf", "-inf" and "n/a" (NaN)
// for the values that have none (a PSNR of an exact image, an undefined SSIM).
inline std::string fixed_text(double v, int decimals = 2) {
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  if (std::isnan(v)) return "n/a";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}

}  // namespace voxcast::cosim
