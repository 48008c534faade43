// Whitecaps on screen (issue 41): the share of a top-down picture of the deep water where the
// renderer draws its Jacobian foam, against Monahan & O'Muircheartaigh's W for the wind, with the
// J_b that ocean/whitecap_coverage.hpp finds for the field (as `nearshore play` sets it).
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>

#include "nearshore/ocean/deep_water.hpp"
#include "nearshore/ocean/sea_state_beaufort.hpp"
#include "nearshore/ocean/whitecap_coverage.hpp"
#include "nearshore/playback/lighting.hpp"
#include "nearshore/playback/water_renderer.hpp"
#include "nearshore/playback/window.hpp"
#include "nearshore/runtime/surface_snapshot.hpp"

namespace nearshore {
namespace {

double whitecap_luminance(const Rgb& c) { return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]; }

// The Beaufort sea both tests draw: three cascades of 128 samples down to 0.5 m waves, seed 1.
ocean::DeepWaterSpecification whitecap_test_sea(const ocean::BeaufortPreset& preset) {
  ocean::DeepWaterSpecification spec;
  spec.spectrum = preset.spectrum;
  spec.grid_size = 128;
  spec.tile_lengths_m = ocean::cascade_tile_lengths_for_m(*preset.spectrum, 128, 3, 0.5);
  spec.seed = 1;
  return spec;
}

TEST(WhitecapRender, TheFoamDrawnCoversWhatMonahanSaysAtTwoWinds) {
  // The deep water `nearshore play` shows at Beaufort 6 and 8 (runtime::BeaufortSea's defaults:
  // 3 cascades of 128^2 down to 0.5 m waves, lambda = 1, seed 1), one keyframe at t = 0, no harbour.
  // Eight views straight down from 80 m, 256 px square (a pixel 0.26 m across: every cascade at
  // full detail, as the J_b was measured), spread over the largest tile. Each view is drawn twice,
  // with the J_b found for W and with no foam (J_b = -1000); a pixel is foam where the first is
  // brighter by more than 0.01 of the display range. The persistent foam map is off
  // (foam_decay_time_s = 0): this is the foam of eq. 3.45 on one frame, the coverage the J_b defines.
  //
  // Expected: W, less the pixels whose foam is too faint to pass 0.01: the shader draws
  // f = f_b mix(T, 1, f_b) with f_b = J_b - J, so just below J_b (f_b < ~0.03, where the foam
  // texture T is low) the foam does not show. Bounds [W / 2, 1.25 W]: half for the faint edge of
  // every patch (J within ~0.03 of J_b is ~20-40 % of the J < J_b area at these J_b) plus the
  // views' sampling noise, inside the factor of several between published data sets; no more foam
  // than W (25 % for the 8 views' sampling of a sea whose crests are 50-100 m apart).
  // Measured (load ~4, 3-6 s): Beaufort 6 2.67 % for W 2.28 %, Beaufort 8 8.64 % for 9.07 %. The
  // pixels brighter by more than 0.25 (foam that reads as white rather than a tint) are printed
  // too: 1.36 and 5.30 % (the water shader draws a crest 0.1 of J past the onset fully white,
  // docs/lighting.md step 7).
  const auto start = std::chrono::steady_clock::now();
  playback::GlWindow window(256, 256, "whitecaps", false);
  playback::WaterRenderer renderer;
  double previous_fraction = 0.0;
  for (int force : {6, 8}) {
    const ocean::BeaufortPreset preset = ocean::beaufort_preset(force);
    const ocean::DeepWaterSpecification spec = whitecap_test_sea(preset);
    ocean::DeepWaterField field(spec);
    field.synthesise(0.0);
    auto keyframe = std::make_shared<runtime::DeepWaterKeyframe>();
    keyframe->serial = static_cast<std::uint64_t>(100 + force);
    for (int c = 0; c < field.cascade_count(); ++c) keyframe->cascades.push_back(field.frame(c));
    ocean::JacobianDistribution distribution;
    distribution.add_frames(keyframe->cascades, 1.0, 65536);
    const double target = ocean::monahan_whitecap_coverage(preset.wind_speed_10_m_s);
    const ocean::FoamOnset onset = ocean::foam_onset_for_coverage(distribution, target);
    ASSERT_FALSE(onset.clamped);

    runtime::SurfaceSnapshot snapshot;
    snapshot.deep_from = snapshot.deep_to = keyframe;
    playback::Lighting foaming;
    foaming.sun_elevation_deg = 50.0;
    foaming.foam_decay_time_s = 0.0;
    foaming.jacobian_foam_onset = onset.jacobian_foam_onset;
    playback::Lighting plain = foaming;
    plain.jacobian_foam_onset = -1000.0;
    long long foam_pixels = 0, white_pixels = 0, pixels = 0;
    const double tile_m = spec.tile_lengths_m.front();
    for (int view = 0; view < 8; ++view) {
      playback::Camera camera;
      const double x = tile_m * std::fmod(0.1 + view * 0.618034, 1.0), y = tile_m * std::fmod(0.3 + view * 0.381966, 1.0);
      camera.eye_m = {x, y, 80.0};
      camera.target_m = {x, y + 0.01, 0.0};  // straight down (the camera wants a horizontal offset)
      renderer.render(snapshot, camera, foaming, 256, 256);
      const Image with_foam = renderer.read_pixels();
      renderer.render(snapshot, camera, plain, 256, 256);
      const Image without = renderer.read_pixels();
      for (int py = 0; py < 256; ++py)
        for (int px = 0; px < 256; ++px) {
          const double brighter = whitecap_luminance(with_foam.get(px, py)) - whitecap_luminance(without.get(px, py));
          foam_pixels += brighter > 0.01;
          white_pixels += brighter > 0.25;  // reported only: foam that reads as white, not a tint
          ++pixels;
        }
    }
    const double fraction = double(foam_pixels) / double(pixels);
    std::printf("Beaufort %d (U10 %.1f m/s): Monahan W %.2f %%, J_b %.3f, foam drawn on %.2f %% of the pixels "
                "(brighter by > 0.25 on %.2f %%)\n", force, preset.wind_speed_10_m_s, 100.0 * target,
                onset.jacobian_foam_onset, 100.0 * fraction, 100.0 * double(white_pixels) / double(pixels));
    EXPECT_GT(fraction, 0.5 * target) << "force " << force;
    EXPECT_LT(fraction, 1.25 * target) << "force " << force;
    EXPECT_GT(fraction, previous_fraction) << "force " << force << ": more wind, more foam";
    previous_fraction = fraction;
  }
  std::printf("wall time %.1f s\n", std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
}

}  // namespace
}  // namespace nearshore

namespace nearshore {
namespace {

// A measurement, not a check (disabled: 27 s; run with --gtest_also_run_disabled_tests): what
// the persistent foam map holds in play. Measured 2026-11-29 (load ~4): Beaufort 6 0.00 % of the
// map above 0.01, Beaufort 8 0.20 %, none above 0.5, against W = 2.3 and 9.1 %: the map's J comes
// from the cascades its 12 m texels resolve (the largest alone), whose J hardly leaves 1, so
// beyond the distance where a pixel resolves the finest cascade the deep water draws almost no
// foam. A shader matter (foam_decay.frag.glsl), reported in docs/lighting.md.
TEST(WhitecapRender, DISABLED_PersistentFoamMapAfterThreeSecondsOfPlay) {
  // What `nearshore play` accumulates:
  // the persistent foam map f_t (foam_decay.frag.glsl, seed 000 eq. 3.46, decay 3 s) after 3 s of
  // display at 30 frames/s, each frame a new keyframe of the same Beaufort sea, with the J_b found
  // for W. The map is one texel per deep sample of the largest tile, view-independent: its share
  // above 0.01 and above 0.5 (foam that reads as white) is the foam play draws where the pixels
  // no longer resolve the fine cascades.
  const auto start = std::chrono::steady_clock::now();
  playback::GlWindow window(64, 64, "whitecaps", false);
  for (int force : {6, 8}) {
    playback::WaterRenderer renderer;
    const ocean::BeaufortPreset preset = ocean::beaufort_preset(force);
    const ocean::DeepWaterSpecification spec = whitecap_test_sea(preset);
    ocean::DeepWaterField field(spec);
    playback::Lighting lighting;
    playback::Camera camera;
    camera.eye_m = {0.0, -50.0, 30.0};
    camera.target_m = {0.0, 100.0, 0.0};
    Raster<float> map(0, 0);
    for (int frame = 0; frame <= 90; ++frame) {
      const double t = frame / 30.0;
      field.synthesise(t);
      auto keyframe = std::make_shared<runtime::DeepWaterKeyframe>();
      keyframe->serial = static_cast<std::uint64_t>(1000 * force + frame);
      keyframe->display_time_s = t;
      for (int c = 0; c < field.cascade_count(); ++c) keyframe->cascades.push_back(field.frame(c));
      if (frame == 0) {
        ocean::JacobianDistribution distribution;
        distribution.add_frames(keyframe->cascades, 1.0, 65536);
        lighting.jacobian_foam_onset =
            ocean::foam_onset_for_coverage(distribution, ocean::monahan_whitecap_coverage(preset.wind_speed_10_m_s))
                .jacobian_foam_onset;
      }
      runtime::SurfaceSnapshot snapshot;
      snapshot.display_time_s = t;
      snapshot.deep_from = snapshot.deep_to = keyframe;
      renderer.render(snapshot, camera, lighting, 64, 64);
    }
    map = renderer.deep_foam_map();
    ASSERT_GT(map.columns(), 0);
    double any = 0, white = 0;
    for (float v : map.values()) any += v > 0.01f, white += v > 0.5f;
    any /= double(map.values().size()), white /= double(map.values().size());
    std::printf("Beaufort %d: Monahan W %.2f %%, J_b %.3f; after 3 s the persistent foam covers %.2f %% (f_t > 0.01), "
                "%.2f %% (f_t > 0.5)\n", force, 100.0 * ocean::monahan_whitecap_coverage(preset.wind_speed_10_m_s),
                lighting.jacobian_foam_onset, 100.0 * any, 100.0 * white);
  }
  std::printf("wall time %.1f s\n", std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
}

}  // namespace
}  // namespace nearshore
