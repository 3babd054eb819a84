#include "refmodel/render/camera.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <glm/geometric.hpp>

namespace voxcast::ref {

CameraFrame make_camera_frame(const CameraDesc& camera, const CameraPose& pose, int width,
                              int height, const Vec3& world_scale) {
  CameraFrame f;
  f.projection = camera.projection;
  f.width = width;
  f.height = height;
  f.eye = pose.eye * world_scale;
  f.forward = glm::normalize(pose.center * world_scale - f.eye);
  f.right = glm::normalize(glm::cross(f.forward, pose.up * world_scale));
  f.up = glm::cross(f.right, f.forward);
  const double aspect = static_cast<double>(width) / static_cast<double>(height);
  f.half_height = camera.projection == Projection::Perspective
                      ? std::tan(camera.fov_deg * std::numbers::pi / 360.0)
                      : 0.5 * camera.height;
  f.half_width = f.half_height * aspect;
  return f;
}

Ray primary_ray(const CameraFrame& f, int px, int py) {
  // Pixel centres on [-1, 1] in both image axes.
  const double u = (2.0 * (px + 0.5) / f.width - 1.0) * f.half_width;
  const double v = (1.0 - 2.0 * (py + 0.5) / f.height) * f.half_height;
  if (f.projection == Projection::Perspective)
    return Ray{f.eye, glm::normalize(f.forward + u * f.right + v * f.up)};
  return Ray{f.eye + u * f.right + v * f.up, f.forward};
}

DepthRange box_depth_range(const CameraFrame& f, const Box& b) {
  DepthRange r{std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
  for (int c = 0; c < 8; ++c) {
    const Vec3 corner{c & 1 ? b.hi.x : b.lo.x, c & 2 ? b.hi.y : b.lo.y, c & 4 ? b.hi.z : b.lo.z};
    const double d = glm::dot(f.forward, corner - f.eye);
    r.near = std::min(r.near, d);
    r.far = std::max(r.far, d);
  }
  return r;
}

Ray origin_plane_ray(const CameraFrame& f, int px, int py, double depth) {
  const Ray ray = primary_ray(f, px, py);
  // forward·direction > 0 for every pixel: the image plane lies in front of the eye.
  return Ray{ray.origin + (depth / glm::dot(f.forward, ray.direction)) * ray.direction,
             ray.direction};
}

CameraPose rotate_about_up(const CameraPose& pose, double angle_deg) {
  const double a = angle_deg * std::numbers::pi / 180.0;
  const Vec3 k = glm::normalize(pose.up);
  const Vec3 r = pose.eye - pose.center;
  // Rodrigues' rotation of the eye offset about k.
  const Vec3 rotated =
      r * std::cos(a) + glm::cross(k, r) * std::sin(a) + k * glm::dot(k, r) * (1.0 - std::cos(a));
  return CameraPose{pose.center + rotated, pose.center, pose.up};
}

}  // namespace voxcast::ref
