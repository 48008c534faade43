#include "nearshore/loops/crossfade.hpp"

#include <fmt/core.h>

#include "nearshore/core/error.hpp"

namespace nearshore::loops {

double crossfade_weight(int k, int crossfade_frames) { return static_cast<double>(k) / (crossfade_frames + 1); }

bool crossfade_blend(int from, int to, int crossfade_frames, int frames_before_jump, BlendSource& blend) {
  if (frames_before_jump < 1 || frames_before_jump > crossfade_frames) return false;
  const int k = crossfade_frames + 1 - frames_before_jump;  // 1 .. c
  blend.source_frame = from - crossfade_frames + k;
  blend.target_frame = to - 1 - crossfade_frames + k;
  blend.target_weight = crossfade_weight(k, crossfade_frames);
  return true;
}

void blend_frames(const sequence::Frame& a, const sequence::Frame& b, double alpha, sequence::Frame& out) {
  const float wa = static_cast<float>(1.0 - alpha), wb = static_cast<float>(alpha);
  auto blend = [&](const Raster<float>& x, const Raster<float>& y, Raster<float>& z, const char* name) {
    if (x.empty() || y.empty()) {
      z = Raster<float>();
      return;
    }
    if (x.columns() != y.columns() || x.rows() != y.rows())
      throw Error(fmt::format("crossfade of frames {} and {}", a.index, b.index),
                  fmt::format("{} is {} x {} in one and {} x {} in the other", name, x.columns(), x.rows(),
                              y.columns(), y.rows()),
                  "blend frames of the same sequence");
    if (z.columns() != x.columns() || z.rows() != x.rows()) z = Raster<float>(x.columns(), x.rows());
    const float* px = x.data();
    const float* py = y.data();
    float* pz = z.data();
    for (std::size_t k = 0; k < x.size(); ++k) pz[k] = wa * px[k] + wb * py[k];
  };
  blend(a.surface_elevation_m, b.surface_elevation_m, out.surface_elevation_m, "surface_elevation");
  blend(a.flux_x_m2_s, b.flux_x_m2_s, out.flux_x_m2_s, "flux_x");
  blend(a.flux_y_m2_s, b.flux_y_m2_s, out.flux_y_m2_s, "flux_y");
  blend(a.breaking, b.breaking, out.breaking, "breaking");
  out.index = -1;
  out.time_s = (1.0 - alpha) * a.time_s + alpha * b.time_s;
}

}  // namespace nearshore::loops
