// Ray setup (VIZARD II section 2.1): "starting with the viewing parameters such
// as eye position, view direction, view up vector, the position of the view
// plane is calculated; for each point P(i,j) of the view plane a ray is cast".
#pragma once

#include "refmodel/math/geometry.hpp"
#include "refmodel/scene/scene.hpp"

namespace voxcast::ref {

// The camera in world space, ready to generate one ray per pixel centre.
struct CameraFrame {
  Projection projection = Projection::Perspective;
  Vec3 eye{0.0};
  Vec3 forward{0.0, 1.0, 0.0};  // unit view direction
  Vec3 right{1.0, 0.0, 0.0};    // unit, image +x
  Vec3 up{0.0, 0.0, 1.0};       // unit, image +y (rows go down)
  double half_width = 1.0;      // perspective: tan(fov/2)*aspect; parallel: world units
  double half_height = 1.0;
  int width = 1, height = 1;
};

// `world_scale` is the volume's normalised spacing (geometry.hpp): camera
// positions are given in voxel coordinates and scaled into world space.
CameraFrame make_camera_frame(const CameraDesc& camera, const CameraPose& pose, int width,
                              int height, const Vec3& world_scale);

// The ray through the centre of pixel (px, py); py = 0 is the top row.
// Perspective rays start at the eye; parallel rays on the plane through the eye
// normal to the view direction. Both travel only forward (t >= 0).
Ray primary_ray(const CameraFrame& frame, int px, int py);

// The smallest and largest depth, forward·(corner - eye), of a world-space
// box's corners: the depth range of everything inside it.
struct DepthRange {
  double near = 0.0, far = 0.0;
};
DepthRange box_depth_range(const CameraFrame& frame, const Box& world_box);

// The float twin of the geometry processor's origin plane (docs/pipeline.md §0):
// pixel (px, py)'s primary ray with its origin moved forward to the plane normal
// to the view direction at depth `depth` (world units) from the eye; the same
// line, the same direction. Sampling it from its clip entry gives the same
// samples as primary_ray when the plane lies in front of the volume.
Ray origin_plane_ray(const CameraFrame& frame, int px, int py, double depth);

// The pose of one eye of a stereo pair: the eye rotated about the up axis
// through the centre by `angle_deg` (VIRIM: two images 4 degrees apart, so each
// eye at +-2).
CameraPose rotate_about_up(const CameraPose& pose, double angle_deg);

}  // namespace voxcast::ref
