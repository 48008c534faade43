// Whitecap coverage (issue 41): Monahan & O'Muircheartaigh's W(U10), and the Jacobian foam onset
// J_b at which a synthesised deep-water field foams that much, checked on other frames than the
// one it was measured on, across the Beaufort presets of seed 000 table 3.1.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>

#include "nearshore/core/error.hpp"
#include "nearshore/ocean/deep_water.hpp"
#include "nearshore/ocean/sea_state_beaufort.hpp"
#include "nearshore/ocean/whitecap_coverage.hpp"

using namespace nearshore;
using namespace nearshore::ocean;

namespace {

/// The deep water `nearshore play` shows for a Beaufort force (runtime::BeaufortSea's defaults,
/// runtime::build_beaufort_field: 3 cascades of 128^2 resolving waves down to 0.5 m, deep, no
/// loop, lambda = 1, seed 1), built here from ocean alone.
std::unique_ptr<DeepWaterField> whitecap_beaufort_field(int force, double choppiness = 1.0) {
  const BeaufortPreset preset = beaufort_preset(force);
  DeepWaterSpecification spec;
  spec.spectrum = preset.spectrum;
  spec.grid_size = 128;
  spec.tile_lengths_m = cascade_tile_lengths_for_m(*preset.spectrum, 128, 3, 0.5);
  spec.choppiness = choppiness;
  spec.seed = 1;
  return std::make_unique<DeepWaterField>(spec);
}

std::vector<DeepWaterFrame> whitecap_frames(DeepWaterField& field, double time_s) {
  field.synthesise(time_s);
  std::vector<DeepWaterFrame> frames;
  for (int c = 0; c < field.cascade_count(); ++c) frames.push_back(field.frame(c));
  return frames;
}

/// J_b measured on the field at t = 0, then the coverage it gives at two later, unrelated times
/// (7.3 s and 19.1 s: a few peak periods on, the crests elsewhere).
struct WhitecapMeasurement {
  FoamOnset onset;
  double later_coverage = 0.0;
};
WhitecapMeasurement measure_whitecaps(DeepWaterField& field, double target_coverage, int samples = 65536) {
  const double lambda = field.specification().choppiness;
  JacobianDistribution now;
  now.add_frames(whitecap_frames(field, 0.0), lambda, samples);
  WhitecapMeasurement measured;
  measured.onset = foam_onset_for_coverage(now, target_coverage);
  JacobianDistribution later;
  for (double t : {7.3, 19.1}) later.add_frames(whitecap_frames(field, t), lambda, samples);
  measured.later_coverage = later.coverage_below(measured.onset.jacobian_foam_onset);
  return measured;
}

}  // namespace

TEST(WhitecapCoverage, MonahanPowerLaw) {
  // W = 3.84e-6 U^3.41: 0.99 % at 10 m/s (the figure every review quotes, "about 1 %"), 0 in a
  // calm, the whole surface from 38.7 m/s.
  EXPECT_NEAR(monahan_whitecap_coverage(10.0), 3.84e-6 * std::pow(10.0, 3.41), 1e-15);
  EXPECT_NEAR(monahan_whitecap_coverage(10.0), 0.0099, 0.0001);
  EXPECT_EQ(monahan_whitecap_coverage(0.0), 0.0);
  EXPECT_EQ(monahan_whitecap_coverage(45.0), 1.0);
  EXPECT_LT(monahan_whitecap_coverage(38.0), 1.0);
  EXPECT_THROW(monahan_whitecap_coverage(-1.0), Error);
  EXPECT_THROW(monahan_whitecap_coverage(std::nan("")), Error);
}

TEST(WhitecapCoverage, BadRequestsAreErrors) {
  JacobianDistribution empty;
  EXPECT_THROW(foam_onset_for_coverage(empty, 1.5), Error);
  EXPECT_THROW(foam_onset_for_coverage(empty, -0.1), Error);
  EXPECT_EQ(foam_onset_for_coverage(empty, 0.01).jacobian_foam_onset, kStokesBreakingJacobian);
  EXPECT_THROW(empty.add_frames({}, 1.0, 10), Error);
  DeepWaterFrame frame;
  frame.grid_size = 8, frame.tile_length_m = 10.0;
  EXPECT_THROW(empty.add_frames({&frame, 1}, 1.0, 0), Error);
}

TEST(WhitecapCoverage, TheFoamOnsetGivesMonahansCoverageAtEveryForce) {
  // Forces 4-12 (the seed's Phillips for 4, unified above), each preset's middle wind. The J_b
  // measured at t = 0 must give, on frames 7 and 19 s later, Monahan's W within a factor 1.5
  // (or, where J_b is clamped, the clamp's coverage within the same factor). Why 1.5: published
  // coverages differ by a factor of several between data sets (Anguelova & Webster 2006), so a
  // renderer inside 1.5 is as close to the sea as the data say anything; what moves our figure is the
  // field's own variation in time and the counting noise of 65536 correlated points (force 4:
  // W = 0.28 %, ~180 points below J_b per frame).
  const auto start = std::chrono::steady_clock::now();
  double previous_coverage = 0.0;
  for (int force : {4, 6, 8, 10, 12}) {
    const double wind_m_s = beaufort_preset(force).wind_speed_10_m_s;
    const double target = monahan_whitecap_coverage(wind_m_s);
    auto field = whitecap_beaufort_field(force);
    const WhitecapMeasurement m = measure_whitecaps(*field, target);
    std::printf("Beaufort %2d, U10 %.1f m/s: Monahan W %.3f %%, J_b %.3f%s, coverage then %.3f %%, later %.3f %%\n", force,
                wind_m_s, 100.0 * target, m.onset.jacobian_foam_onset, m.onset.clamped ? " (clamped)" : "",
                100.0 * m.onset.coverage, 100.0 * m.later_coverage);
    const double expected = m.onset.clamped ? m.onset.coverage : target;
    EXPECT_GT(m.later_coverage, expected / 1.5) << "force " << force;
    EXPECT_LT(m.later_coverage, expected * 1.5) << "force " << force;
    if (!m.onset.clamped) {
      EXPECT_GT(m.later_coverage, target / 1.5) << "force " << force;
    }
    EXPECT_GT(m.later_coverage, previous_coverage) << "force " << force << ": coverage must rise with the wind";
    previous_coverage = m.later_coverage;
  }
  std::printf("wall time %.1f s\n", std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
}

TEST(WhitecapCoverage, TheSeedsBeaufortTableReadsTheSame) {
  // Seed 000 table 3.1 in words: force 1 "ripples, crests do not foam", force 10 "the sea surface
  // is white", force 12 "the whole sea is white". With J_b from Monahan's W: force 1 foams on
  // under 0.01 % of the surface, forces 10 and 12 on well over 10 %.
  for (int force : {1, 10, 12}) {
    auto field = whitecap_beaufort_field(force);
    const WhitecapMeasurement m = measure_whitecaps(*field, monahan_whitecap_coverage(beaufort_preset(force).wind_speed_10_m_s));
    std::printf("Beaufort %2d: coverage %.4f %% (J_b %.3f)\n", force, 100.0 * m.later_coverage, m.onset.jacobian_foam_onset);
    if (force == 1) {
      EXPECT_LT(m.later_coverage, 1e-4);
    } else {
      EXPECT_GT(m.later_coverage, 0.10) << "force " << force;
    }
  }
}

TEST(WhitecapCoverage, HoldsForAnySpectrumAndChoppiness) {
  // The J_b comes from the field's own J distribution: a JONSWAP swell with cos-2s spreading at
  // lambda = 0.6, and the force 8 preset at lambda = 1.6, both asked for 1 % (U10 ~ 10 m/s),
  // foam on 1 % of the surface 7 and 19 s later (factor 1.5, as above).
  auto jonswap = std::make_shared<DirectionalWavenumberSpectrum>(std::make_shared<JonswapSpectrum>(3.0, 9.0, 3.3),
                                                                 std::make_shared<CosineSquaredSpreading>(0.3, 10.0));
  DeepWaterSpecification spec;
  spec.spectrum = jonswap;
  spec.grid_size = 128;
  spec.tile_lengths_m = cascade_tile_lengths_for_m(*jonswap, 128, 3, 0.5);
  spec.choppiness = 0.6;
  DeepWaterField swell(spec);
  auto storm = whitecap_beaufort_field(8, 1.6);
  for (DeepWaterField* field : {&swell, storm.get()}) {
    const WhitecapMeasurement m = measure_whitecaps(*field, 0.01);
    std::printf("lambda %.1f: J_b %.3f, coverage later %.3f %%\n", field->specification().choppiness,
                m.onset.jacobian_foam_onset, 100.0 * m.later_coverage);
    EXPECT_FALSE(m.onset.clamped);
    EXPECT_GT(m.later_coverage, 0.01 / 1.5);
    EXPECT_LT(m.later_coverage, 0.01 * 1.5);
  }
}

TEST(WhitecapCoverage, TheTrackerMeasuresOnlyWhenTheSeaOrTheWindChanges) {
  // What `nearshore play` calls every frame: a J_b on the first frame, none while the sea and the
  // wind stay, a new one (higher: more wind, more foam) when the wind rises, and one for another sea.
  auto moderate = whitecap_beaufort_field(6);
  auto gale = whitecap_beaufort_field(8);
  const std::vector<DeepWaterFrame> frames = whitecap_frames(*moderate, 0.0), later = whitecap_frames(*moderate, 1.0);
  WhitecapFoamOnset tracker;
  EXPECT_FALSE(tracker.update({}, 1.0, 12.8).has_value());
  const auto first = tracker.update(frames, 1.0, 12.8);
  ASSERT_TRUE(first.has_value());
  EXPECT_NEAR(first->coverage, monahan_whitecap_coverage(12.8), 1e-4);
  EXPECT_FALSE(tracker.update(later, 1.0, 12.8).has_value());
  const auto windier = tracker.update(later, 1.0, 19.2);
  ASSERT_TRUE(windier.has_value());
  EXPECT_GT(windier->jacobian_foam_onset, first->jacobian_foam_onset);
  EXPECT_TRUE(tracker.update(whitecap_frames(*gale, 0.0), 1.0, 19.2).has_value());
}
