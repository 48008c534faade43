#pragma once
// Camera: where the viewer stands and looks, in the SITE frame (runtime/surface_snapshot.hpp:
// metres east (x) and north (y) of the harbour grid's south-west corner, z up from still water),
// and CameraView: its matrices on a viewport, the one place the grids (surface_grids.hpp) and
// the renderer get them from. GL-free: the grids' CPU logic is tested without a GPU.
//
// Precision: the site frame keeps float32 (the GPU's precision) at about a millimetre within
// 10 km of the corner and a centimetre within 100 km; projected coordinates (UTM, ~4e6 m) would
// lose half a metre, which is why nothing here is projected.
#include <array>

#include "nearshore/core/raster.hpp"
#include "nearshore/playback/vector3.hpp"

namespace nearshore::playback {

/// A 4 x 4 matrix, column-major (OpenGL's order: element (row r, column c) at [c * 4 + r]).
using Matrix4 = std::array<double, 16>;

struct Camera {
  Vector3 eye_m = {0, 0, 100};     ///< viewer position, site frame (x east, y north, z up), metres
  Vector3 target_m = {0, 100, 0};  ///< the point looked at (not straight above or below the eye)
  double vertical_field_of_view_deg = 45.0;
  /// Clip distances (m). 0 = chosen by the renderer: near from the eye's height, far at the
  /// grid's reach (radial, quadtree) or just beyond the Earth's horizon (projected grid).
  double near_m = 0.0, far_m = 0.0;

  /// A viewpoint offshore to the south-south-west of a harbour of `width_m` x `height_m` (site
  /// frame), looking into it from a height of about a quarter of its extent: the view a pilot
  /// boarding from seaward would have.
  static Camera overlooking_site(double width_m, double height_m);
};

/// A camera on a viewport: everything the grids and the shaders need of it.
struct CameraView {
  Vector3 eye_m{};
  Vector3 forward{}, right{}, up{};  ///< unit vectors of the camera (right-handed, z up)
  int width_px = 0, height_px = 0;
  double near_m = 0.0, far_m = 0.0;
  /// Focal length in pixels: viewport height / (2 tan(fov / 2)). A length s at distance d spans
  /// s * focal_length_px / d pixels; the grids turn their screen-space error into metres with it.
  double focal_length_px = 0.0;
  Matrix4 view{}, projection{}, view_projection{};
  /// The projection times the view's rotation only (no translation): maps eye-relative points, so
  /// a shader can turn a screen point into a ray direction without subtracting large numbers.
  Matrix4 rotation_projection{};
  /// The six clip planes (a, b, c, d) with a x + b y + c z + d >= 0 inside (left, right, bottom,
  /// top, near, far), normalised so that (a, b, c) is a unit vector.
  std::array<std::array<double, 4>, 6> frustum_planes{};
};

/// Perspective view of `camera` on a width_px x height_px viewport with the given clip distances.
/// Throws nearshore::Error when the eye and the target coincide or the look is vertical.
CameraView camera_view(const Camera& camera, int width_px, int height_px, double near_m, double far_m);

/// The view of a host's own camera (a scene graph's: OpenSceneGraph, a game engine), from its
/// view and perspective projection matrices (column-major, OpenGL's conventions: the view maps
/// the site frame to eye space, the eye looks down -z; the projection maps depth to [-1, 1]) on a
/// width_px x height_px viewport. The clip distances are read back from the projection (n =
/// P[14] / (P[10] - 1), f = P[14] / (P[10] + 1)), so the sea is depth-tested in the host's own
/// depth range. For the matrices camera_view(camera, ...) makes it returns that view again (to
/// round-off). Throws nearshore::Error for a projection that is not a perspective one (an
/// orthographic P[15] = 1, or n, f not 0 < n < f) or a view that is not a rigid motion.
CameraView camera_view_from_matrices(const Matrix4& view, const Matrix4& projection, int width_px, int height_px);

/// A top-down orthographic view of the site rectangle [x0, x1] x [y0, y1] (row 0 of the viewport
/// at y0, the south), z in [z_min, z_max]: the height pass.
Matrix4 orthographic_top_down(double x0_m, double y0_m, double x1_m, double y1_m, double z_min_m, double z_max_m);

Matrix4 multiply(const Matrix4& a, const Matrix4& b);
Matrix4 inverse(const Matrix4& m);
/// m * (x, y, z, w).
std::array<double, 4> transform(const Matrix4& m, const std::array<double, 4>& point);

/// The distance at which a sphere of radius `earth_radius_m` drops out of sight from an eye
/// `eye_height_m` above it: sqrt(h (2R + h)) (the tangent's length), and the horizon's dip below
/// the horizontal, acos(R / (R + h)) (seed 002 section 3: the sphere the projected grid lies on).
double horizon_distance_m(double eye_height_m, double earth_radius_m);
double horizon_dip_rad(double eye_height_m, double earth_radius_m);

}  // namespace nearshore::playback
