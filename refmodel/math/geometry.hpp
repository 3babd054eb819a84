// Rays, boxes and the ray–box clip of the ray-setup stage (VIZARD II section 2.1).
//
// World space is the voxel grid scaled by the normalised spacing (spacing divided
// by the smallest spacing), so one world unit is the smallest voxel edge and an
// isotropic volume's world and voxel coordinates coincide. Distances along rays,
// the sampling distance 1/oversampling and the opacity unit ("alpha per voxel")
// are all in world units.
#pragma once

#include <optional>

#include <glm/vec3.hpp>

namespace voxcast::ref {

using Vec3 = glm::dvec3;

struct Ray {
  Vec3 origin;     // world coordinates
  Vec3 direction;  // unit length
  Vec3 at(double t) const { return origin + t * direction; }
};

struct Box {
  Vec3 lo, hi;  // inclusive corners, lo <= hi per axis
};

// The part of a ray inside a box, t_enter <= t_exit, both >= t_min.
struct Segment {
  double t_enter = 0.0;
  double t_exit = 0.0;
  double length() const { return t_exit - t_enter; }
};

// Slab clip of `ray` against `box`, keeping t >= t_min (0: the eye plane; the
// eye may be inside the box). A direction component of exactly zero is a ray
// parallel to that slab pair: it is inside iff its origin is (no division by
// zero, so rays exactly along an axis or a face are handled exactly).
std::optional<Segment> clip(const Ray& ray, const Box& box, double t_min = 0.0);

}  // namespace voxcast::ref
