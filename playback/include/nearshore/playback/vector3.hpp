#pragma once
// The playback's 3-vectors (directions to the sun, the eye, normals; camera positions in metres):
// one type and its two operations, shared by the camera, the sky, the lighting and the BRDF.
#include <array>
#include <cmath>

namespace nearshore::playback {

using Vector3 = std::array<double, 3>;

inline double dot(const Vector3& a, const Vector3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/// v / |v| (v must not be zero).
inline Vector3 normalize(const Vector3& v) {
  const double length = std::sqrt(dot(v, v));
  return {v[0] / length, v[1] / length, v[2] / length};
}

}  // namespace nearshore::playback
