#include "nearshore/playback/camera.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "nearshore/core/error.hpp"

namespace nearshore::playback {

namespace {
Eigen::Matrix4d to_eigen(const Matrix4& m) { return Eigen::Map<const Eigen::Matrix4d>(m.data()); }
Matrix4 from_eigen(const Eigen::Matrix4d& m) {
  Matrix4 out;
  Eigen::Map<Eigen::Matrix4d>(out.data()) = m;
  return out;
}
// Gribb & Hartmann: the six clip planes are sums and differences of view_projection's rows.
void set_frustum_planes(CameraView& v) {
  const Eigen::Matrix4d m = to_eigen(v.view_projection);
  const Eigen::RowVector4d planes[6] = {m.row(3) + m.row(0), m.row(3) - m.row(0), m.row(3) + m.row(1),
                                        m.row(3) - m.row(1), m.row(3) + m.row(2), m.row(3) - m.row(2)};
  for (int i = 0; i < 6; ++i) {
    const double length = planes[i].head<3>().norm();
    for (int c = 0; c < 4; ++c) v.frustum_planes[std::size_t(i)][std::size_t(c)] = planes[i][c] / length;
  }
}
}  // namespace

Camera Camera::overlooking_site(double width_m, double height_m) {
  const double extent = std::max(width_m, height_m);
  Camera camera;
  camera.target_m = {0.5 * width_m, 0.62 * height_m, 0.0};
  camera.eye_m = {0.30 * width_m, -0.22 * height_m, 0.26 * extent};
  return camera;
}

Matrix4 multiply(const Matrix4& a, const Matrix4& b) { return from_eigen(to_eigen(a) * to_eigen(b)); }
Matrix4 inverse(const Matrix4& m) { return from_eigen(to_eigen(m).inverse()); }
std::array<double, 4> transform(const Matrix4& m, const std::array<double, 4>& p) {
  const Eigen::Vector4d r = to_eigen(m) * Eigen::Vector4d(p[0], p[1], p[2], p[3]);
  return {r[0], r[1], r[2], r[3]};
}

CameraView camera_view(const Camera& camera, int width_px, int height_px, double near_m, double far_m) {
  const Eigen::Vector3d eye(camera.eye_m[0], camera.eye_m[1], camera.eye_m[2]);
  const Eigen::Vector3d target(camera.target_m[0], camera.target_m[1], camera.target_m[2]);
  const Eigen::Vector3d look = target - eye;
  if (look.norm() <= 0.0 || look.head<2>().norm() <= 1e-9 * look.norm())
    throw Error("camera", "looks straight up or down, or at its own eye (eye (" + std::to_string(eye.x()) + ", " +
                              std::to_string(eye.y()) + ", " + std::to_string(eye.z()) + ") m)",
                "give the target a horizontal offset from the eye");
  if (width_px <= 0 || height_px <= 0 || !(near_m > 0.0) || !(far_m > near_m))
    throw Error("camera", "viewport " + std::to_string(width_px) + " x " + std::to_string(height_px) + " with near " +
                              std::to_string(near_m) + " m and far " + std::to_string(far_m) + " m",
                "give a viewport of at least 1 x 1 pixel and 0 < near < far");
  CameraView v;
  v.eye_m = camera.eye_m;
  v.width_px = width_px;
  v.height_px = height_px;
  v.near_m = near_m;
  v.far_m = far_m;
  const Eigen::Vector3d forward = look.normalized();
  const Eigen::Vector3d right = forward.cross(Eigen::Vector3d::UnitZ()).normalized();  // z is up
  const Eigen::Vector3d up = right.cross(forward);
  v.forward = {forward.x(), forward.y(), forward.z()};
  v.right = {right.x(), right.y(), right.z()};
  v.up = {up.x(), up.y(), up.z()};
  Eigen::Matrix4d rotation = Eigen::Matrix4d::Identity();
  rotation.block<1, 3>(0, 0) = right.transpose();
  rotation.block<1, 3>(1, 0) = up.transpose();
  rotation.block<1, 3>(2, 0) = -forward.transpose();
  Eigen::Matrix4d translation = Eigen::Matrix4d::Identity();
  translation.block<3, 1>(0, 3) = -eye;
  const double tan_half = std::tan(camera.vertical_field_of_view_deg * std::numbers::pi / 360.0);
  const double f = 1.0 / tan_half, aspect = double(width_px) / height_px;
  Eigen::Matrix4d projection = Eigen::Matrix4d::Zero();
  projection(0, 0) = f / aspect;
  projection(1, 1) = f;
  projection(2, 2) = (far_m + near_m) / (near_m - far_m);
  projection(2, 3) = 2.0 * far_m * near_m / (near_m - far_m);
  projection(3, 2) = -1.0;
  v.focal_length_px = 0.5 * height_px / tan_half;
  v.view = from_eigen(rotation * translation);
  v.projection = from_eigen(projection);
  v.view_projection = from_eigen(projection * rotation * translation);
  v.rotation_projection = from_eigen(projection * rotation);
  set_frustum_planes(v);
  return v;
}

CameraView camera_view_from_matrices(const Matrix4& view, const Matrix4& projection, int width_px, int height_px) {
  const Eigen::Matrix4d p = to_eigen(projection), w = to_eigen(view);
  const double near_m = p(2, 3) / (p(2, 2) - 1.0), far_m = p(2, 3) / (p(2, 2) + 1.0);
  if (width_px <= 0 || height_px <= 0 || p(3, 2) != -1.0 || p(3, 3) != 0.0 || !(near_m > 0.0) || !(far_m > near_m) ||
      !(p(1, 1) > 0.0))
    throw Error("host camera", "projection with P[10] = " + std::to_string(p(2, 2)) + ", P[11] = " +
                                   std::to_string(p(3, 2)) + ", P[14] = " + std::to_string(p(2, 3)) + ", P[15] = " +
                                   std::to_string(p(3, 3)) + " on a viewport of " + std::to_string(width_px) + " x " +
                                   std::to_string(height_px) + " px",
                "give a perspective projection (glFrustum / gluPerspective form) with 0 < near < far and a viewport of "
                "at least 1 x 1 pixel");
  const Eigen::Matrix3d rotation = w.topLeftCorner<3, 3>();
  if (!(rotation * rotation.transpose()).isIdentity(1e-6) || !(rotation.determinant() > 0.0) ||
      w.row(3) != Eigen::RowVector4d(0, 0, 0, 1))
    throw Error("host camera", "view matrix is not a rigid motion (it scales, shears or mirrors)",
                "pass the camera's view matrix alone (no model scaling in it)");
  CameraView v;
  const Eigen::Vector3d eye = -rotation.transpose() * w.block<3, 1>(0, 3);
  v.eye_m = {eye.x(), eye.y(), eye.z()};
  v.right = {rotation(0, 0), rotation(0, 1), rotation(0, 2)};
  v.up = {rotation(1, 0), rotation(1, 1), rotation(1, 2)};
  v.forward = {-rotation(2, 0), -rotation(2, 1), -rotation(2, 2)};
  v.width_px = width_px;
  v.height_px = height_px;
  v.near_m = near_m;
  v.far_m = far_m;
  v.focal_length_px = 0.5 * height_px * p(1, 1);  // P[5] = 1 / tan(fov / 2)
  Eigen::Matrix4d rotation_only = Eigen::Matrix4d::Identity();
  rotation_only.topLeftCorner<3, 3>() = rotation;
  v.view = view;
  v.projection = projection;
  v.view_projection = from_eigen(p * w);
  v.rotation_projection = from_eigen(p * rotation_only);
  set_frustum_planes(v);
  return v;
}

Matrix4 orthographic_top_down(double x0, double y0, double x1, double y1, double z_min, double z_max) {
  // Looking down -z: eye-space depth is -z, so nearer points are higher ones (the surface seen).
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m(0, 0) = 2.0 / (x1 - x0);
  m(0, 3) = -(x1 + x0) / (x1 - x0);
  m(1, 1) = 2.0 / (y1 - y0);
  m(1, 3) = -(y1 + y0) / (y1 - y0);
  m(2, 2) = -2.0 / (z_max - z_min);  // z_max -> -1 (near), z_min -> +1 (far)
  m(2, 3) = (z_max + z_min) / (z_max - z_min);
  return from_eigen(m);
}

double horizon_distance_m(double h, double r) { return std::sqrt(std::max(h, 0.0) * (2.0 * r + std::max(h, 0.0))); }
// acos(R / (R + h)) written as atan2(sqrt(h (2R + h)), R): the same angle, well conditioned for h << R.
double horizon_dip_rad(double h, double r) { return std::atan2(horizon_distance_m(h, r), r); }

}  // namespace nearshore::playback
