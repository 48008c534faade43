#pragma once
// Shared by the ships tests: scratch folders and a sea of one regular wave carried by a real
// deep-water keyframe (ocean::DeepWaterField rebuilt from a one-coefficient lattice), so a ship
// samples it through runtime::SurfaceSampler exactly as it samples the sea the renderer draws.
#include <cmath>
#include <filesystem>
#include <functional>
#include <memory>
#include <numbers>
#include <string>

#include <gtest/gtest.h>

#include "nearshore/core/error.hpp"
#include "nearshore/ocean/deep_water.hpp"
#include "nearshore/runtime/surface_sampler.hpp"

namespace nearshore::ships::testing {

namespace fs = std::filesystem;

/// Gravity as the ships library's parameters default it (ShallowWaterOptions, WaterProperties).
inline constexpr double kG = 9.81;

/// The message of the nearshore::Error `f` throws ("" when it throws none).
inline std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

inline fs::path scratch_folder() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const fs::path folder = fs::path(NEARSHORE_BINARY_DIR) / "tests" / "ships" / "scratch" /
                          (std::string(info->test_suite_name()) + "." + info->name());
  fs::remove_all(folder);
  fs::create_directories(folder);
  return folder;
}

/// eta = a cos(k x - w t), w^2 = g k (deep water), travelling east: one lattice coefficient
/// (n, m) = (1, 0) of a tile one wavelength long.
class RegularWave {
 public:
  RegularWave(double amplitude_m, double wavelength_m, int grid_size = 64) {
    ocean::RecordedDeepWater recorded;
    ocean::RecordedCascade c;
    c.grid_size = grid_size;
    c.tile_length_m = wavelength_m;
    const std::size_t n2 = static_cast<std::size_t>(grid_size) * grid_size;
    c.amplitude_m.assign(n2, 0.0f);
    c.phase_rad.assign(n2, 0.0);
    c.angular_frequency_rad_s.assign(n2, 0.0);
    c.harmonic.assign(n2, -1);
    const double k = 2.0 * std::numbers::pi / wavelength_m;
    angular_frequency_rad_s_ = std::sqrt(9.81 * k);
    c.amplitude_m[1] = static_cast<float>(amplitude_m);  // row 0 (ky = 0), column 1 (kx = 2 pi / L)
    c.angular_frequency_rad_s[1] = angular_frequency_rad_s_;
    recorded.cascades.push_back(c);
    recorded.choppiness = 1.0;
    field_ = std::make_unique<ocean::DeepWaterField>(recorded);
  }
  double angular_frequency_rad_s() const { return angular_frequency_rad_s_; }

  /// The snapshot of the sea at time t (one deep keyframe, no harbour).
  runtime::SurfaceSnapshot snapshot(double time_s) {
    auto keyframe = std::make_shared<runtime::DeepWaterKeyframe>();
    keyframe->serial = ++serial_;
    keyframe->display_time_s = time_s;
    field_->synthesise(time_s);
    keyframe->cascades = {field_->frame(0)};
    runtime::SurfaceSnapshot s;
    s.display_time_s = time_s;
    s.deep_from = keyframe;
    s.deep_to = keyframe;
    return s;
  }

 private:
  std::unique_ptr<ocean::DeepWaterField> field_;
  double angular_frequency_rad_s_ = 0.0;
  std::uint64_t serial_ = 0;
};

}  // namespace nearshore::ships::testing
