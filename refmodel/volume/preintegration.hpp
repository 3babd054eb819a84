// Pre-integrated classification (Engel, Kraus, Ertl, "High-Quality
// Pre-Integrated Volume Rendering Using Hardware-Accelerated Pixel Shading",
// Graphics Hardware 2001): the transfer function integrated over the segment
// between two consecutive samples, assuming the value varies linearly from
// the front sample's s_f to the back sample's s_b. The float twin of the
// pre-integration table (issue 25): the exact integral, to double precision.
//
// With alpha given per unit distance (transfer_function.hpp), the extinction
// is tau(s) = -ln(1 - alpha(s)), so a constant value over a length L gives
// 1 - (1 - alpha)^L: the compositor's opacity correction. Over the segment
// x in [0, L], s(x) = s_f + (s_b - s_f) x / L, the optical depth is
// D(x) = int_0^x tau(s(x')) dx', and
//
//   alpha_seg = 1 - exp(-D(L))
//   C_seg     = int_0^L c(s(x)) tau(s(x)) exp(-D(x)) dx     (premultiplied:
//               Engel et al.'s self-attenuated colour)
//
// Between control points alpha and c are linear in s (a ramp) or constant (a
// binary function), so D has a closed form on each piece, and integrating by
// parts (tau exp(-D) = d/dx of -exp(-D)) leaves only int exp(-D) dx times
// the colour's slope, a smooth integrand integrated adaptively.
#pragma once

#include <glm/vec3.hpp>

#include "refmodel/volume/transfer_function.hpp"

namespace voxcast::ref {

struct SegmentClass {
  glm::dvec3 premultiplied{0.0};  // C_seg
  double alpha = 0.0;             // alpha_seg, already for the segment's length
  // The colour the compositor multiplies by alpha: C_seg / alpha_seg (0 where
  // the segment is transparent).
  glm::dvec3 color() const;
};

// The segment from a sample of value `front` to the next of value `back`,
// `length` world units long (the step), through `tf` (values in the units of
// its points). length >= 0; a length of 0 is transparent.
SegmentClass preintegrate(const TransferFunction& tf, double front, double back, double length);

}  // namespace voxcast::ref
