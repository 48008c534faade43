// The FFT deep-water field: Hs by integration, cascades, exact looping, seamless tiles,
// dispersion, Jacobian and foam, against closed forms and a direct sum of the same components.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <numbers>

#include "nearshore/bake/deep_water_record.hpp"
#include "nearshore/ocean/deep_water.hpp"
#include "nearshore/bake/deep_water_tiles.hpp"
#include "nearshore/ocean/sea_state_beaufort.hpp"
#include "nearshore/core/error.hpp"
#include "nearshore/sequence/deep_water_section.hpp"
#include "nearshore/sequence/sequence_reader.hpp"

using namespace nearshore;
using namespace nearshore::ocean;
using namespace nearshore::bake;

namespace {

/// Every spectrum the field can take, at a moderate sea (Beaufort 6-ish), each one line.
std::vector<std::shared_ptr<const WavenumberSpectrum>> every_spectrum() {
  auto jonswap = std::make_shared<JonswapSpectrum>(3.0, 9.0, 3.3);
  auto spreading = std::make_shared<CosineSquaredSpreading>(0.3, 10.0);
  return {
      std::make_shared<PhillipsSpectrum>(PhillipsSpectrum::amplitude_for_significant_wave_height(3.0, 12.0), 12.0, 0.3),
      std::make_shared<UnifiedSpectrum>(12.8, 1.0, 0.3),
      std::make_shared<PmIttcSpectrum>(12.0, 0.3),
      std::make_shared<DirectionalWavenumberSpectrum>(jonswap, spreading),
      std::make_shared<DirectionalWavenumberSpectrum>(std::make_shared<TmaSpectrum>(jonswap, 20.0), spreading, 20.0),
  };
}

DeepWaterSpecification specification_for(std::shared_ptr<const WavenumberSpectrum> spectrum, int grid_size,
                                         double largest_tile_m, int cascades = 4) {
  DeepWaterSpecification spec;
  spec.spectrum = std::move(spectrum);
  spec.grid_size = grid_size;
  spec.tile_lengths_m = cascade_tile_lengths_m(largest_tile_m, cascades, 4.0);
  spec.seed = 7;
  return spec;
}

double spatial_variance_m2(const DeepWaterField& field) {
  double total = 0.0;
  for (int c = 0; c < field.cascade_count(); ++c) {
    const auto& eta = field.frame(c).surface_elevation_m;
    double mean = 0.0, square = 0.0;
    for (float v : eta) mean += v, square += static_cast<double>(v) * v;
    mean /= eta.size();
    total += square / eta.size() - mean * mean;
  }
  return total;
}

/// The direct sum of the field's components at (x, y, t): what the FFT must reproduce.
struct DirectSum {
  double eta = 0, dx = 0, dy = 0, sx = 0, sy = 0, dxx = 0, dyy = 0, dxy = 0;
};
DirectSum direct_sum(const SeaState& sea, double depth_m, double x, double y, double t) {
  DirectSum sum;
  for (const WaveComponent& c : sea.components) {
    const double k = wavenumber_from_frequency(c.angular_frequency_rad_s, depth_m);
    const double ux = std::cos(c.direction_rad), uy = std::sin(c.direction_rad);
    const double phase = k * (ux * x + uy * y) - c.angular_frequency_rad_s * t + c.phase_rad;
    const double cosine = c.amplitude_m * std::cos(phase), sine = c.amplitude_m * std::sin(phase);
    sum.eta += cosine;
    sum.dx -= ux * sine;  // Re(i u a e^{i phase}) = -u a sin(phase): crests sharpen
    sum.dy -= uy * sine;
    sum.sx -= k * ux * sine;
    sum.sy -= k * uy * sine;
    sum.dxx -= k * ux * ux * cosine;
    sum.dyy -= k * uy * uy * cosine;
    sum.dxy -= k * ux * uy * cosine;
  }
  return sum;
}

}  // namespace

TEST(WavenumberSpectrum, ClosedFormVariances) {
  // Phillips: m0 = A pi Lw^2 / 2 (eq. 2.4 integrated); the l = 1e-3 Lw cut-off removes ~2e-6 of it.
  const PhillipsSpectrum phillips(PhillipsSpectrum::amplitude_for_significant_wave_height(2.0, 10.0), 10.0, 0.0);
  EXPECT_NEAR(phillips.significant_wave_height_m(), 2.0, 2e-4);
  // PM-ITTC (seed 001 eq. 19): m0 = alpha U^4 / (4 * 0.688 g^2).
  const PmIttcSpectrum ittc(15.0, 1.0);
  const double ittc_hs = 4.0 * std::sqrt(8.1e-3 * std::pow(15.0, 4) / (4.0 * 0.688 * kGravity_m_s2 * kGravity_m_s2));
  EXPECT_NEAR(ittc.significant_wave_height_m(), ittc_hs, 1e-4 * ittc_hs);
  // Frequency -> wavenumber (seed 001 eq. 17) keeps the variance: JONSWAP Hs = 3 m, deep and at
  // 20 m depth (where the TMA spectrum is the one to compare with). 1e-3: quadrature of a peak
  // of relative width 0.07 on the polar grid.
  auto jonswap = std::make_shared<JonswapSpectrum>(3.0, 9.0, 3.3);
  auto spreading = std::make_shared<CosineSquaredSpreading>(0.3, 10.0);
  EXPECT_NEAR(DirectionalWavenumberSpectrum(jonswap, spreading).significant_wave_height_m(), 3.0, 3e-3);
  auto tma = std::make_shared<TmaSpectrum>(jonswap, 20.0);
  EXPECT_NEAR(DirectionalWavenumberSpectrum(tma, spreading, 20.0).significant_wave_height_m(),
              tma->significant_wave_height_m(), 1e-3 * tma->significant_wave_height_m());
}

TEST(WavenumberSpectrum, SpreadingsIntegrateToOneAndFoldingKeepsTheVariance) {
  // The closed-form S(k) of each spectrum equals the quadrature of Psi k over the circle, i.e. the
  // spreading (Elfouhaily's 1 + Delta cos 2 theta, the folded half-planes) integrates to 1.
  const UnifiedSpectrum downwind(12.0, 1.2, 0.4), both(12.0, 1.2, 0.4, WindHalfPlane::kBothWays);
  const PhillipsSpectrum phillips(1e-3, 8.0, -0.5);
  for (double k : {0.03, 0.08, 0.5, 5.0, 400.0}) {
    EXPECT_NEAR(downwind.WavenumberSpectrum::omnidirectional_density_m3(k), downwind.omnidirectional_density_m3(k),
                1e-9 * downwind.omnidirectional_density_m3(k));
    EXPECT_NEAR(both.WavenumberSpectrum::omnidirectional_density_m3(k), both.omnidirectional_density_m3(k),
                1e-9 * both.omnidirectional_density_m3(k));
    EXPECT_NEAR(phillips.WavenumberSpectrum::omnidirectional_density_m3(k), phillips.omnidirectional_density_m3(k),
                1e-9 * phillips.omnidirectional_density_m3(k) + 1e-300);
  }
  // Folded: nothing travels up-wind.
  EXPECT_EQ(downwind.density_m4(-0.1 * std::cos(0.4), -0.1 * std::sin(0.4)), 0.0);
  EXPECT_GT(both.density_m4(-0.1 * std::cos(0.4), -0.1 * std::sin(0.4)), 0.0);
}

TEST(WavenumberSpectrum, SumOfIndependentSeasAddsVariances) {
  // A swell (Hs 1 m, Tp 7 s, s = 75) and a local wind sea (Hs 0.6 m, Tp 3.5 s, s = 20), the case of
  // issue 14: independent seas, so Psi adds and Hs^2 = 1.0^2 + 0.6^2 (1e-3: each part's quadrature,
  // as above). The longest waves set the ranges; the most energetic part the mean direction.
  auto swell = std::make_shared<DirectionalWavenumberSpectrum>(std::make_shared<JonswapSpectrum>(1.0, 7.0, 3.3),
                                                               std::make_shared<CosineSquaredSpreading>(-1.2, 75.0));
  auto wind_sea = std::make_shared<DirectionalWavenumberSpectrum>(std::make_shared<JonswapSpectrum>(0.6, 3.5, 3.3),
                                                                  std::make_shared<CosineSquaredSpreading>(-1.0, 20.0));
  const SpectrumSum sum({swell, wind_sea});
  EXPECT_NEAR(sum.significant_wave_height_m(), std::hypot(1.0, 0.6), 1e-3 * std::hypot(1.0, 0.6));
  EXPECT_EQ(sum.peak_wavenumber_rad_m(), swell->peak_wavenumber_rad_m());
  EXPECT_EQ(sum.mean_direction_rad(), -1.2);
  for (double k : {0.05, 0.1, 0.33, 1.0})
    EXPECT_DOUBLE_EQ(sum.density_m4(k * std::cos(-1.1), k * std::sin(-1.1)),
                     swell->density_m4(k * std::cos(-1.1), k * std::sin(-1.1)) + wind_sea->density_m4(k * std::cos(-1.1), k * std::sin(-1.1)));
  EXPECT_EQ(sum.to_json()["parts"].size(), 2u);
  // The FFT field made from the sum holds both seas (3 %, the field test below).
  DeepWaterField field(specification_for(std::make_shared<SpectrumSum>(std::vector<std::shared_ptr<const WavenumberSpectrum>>{swell, wind_sea}), 64,
                                         10.0 * 2.0 * std::numbers::pi / sum.peak_wavenumber_rad_m()));
  EXPECT_NEAR(field.significant_wave_height_m(), sum.significant_wave_height_m(), 0.03 * sum.significant_wave_height_m());
  EXPECT_THROW(SpectrumSum({}), nearshore::Error);
}

TEST(DeepWaterField, HsIsTheSpectrumsAndDoesNotMoveWithNOrL) {
  // Seed 001's claim: amplitudes from the cell integrals make Hs independent of N and L. For
  // every spectrum, 4 cascades with the largest tile 10 peak wavelengths long: the field's Hs
  // (from the FFT frames' spatial variance) is within 3 % of 4 sqrt(m0) (issue 5), and again
  // after doubling N and after halving L. The lattices miss only the variance below half the
  // first cell (exp(-100)-small) and above the last Nyquist (< 0.5 % of m0 here).
  for (const auto& spectrum : every_spectrum()) {
    const double spectrum_hs = spectrum->significant_wave_height_m();
    const double peak_wavelength_m = 2.0 * std::numbers::pi / spectrum->peak_wavenumber_rad_m();
    for (auto [grid_size, largest_tile_m] : {std::pair{64, 10.0 * peak_wavelength_m}, std::pair{128, 10.0 * peak_wavelength_m},
                                            std::pair{64, 5.0 * peak_wavelength_m}}) {
      DeepWaterField field(specification_for(spectrum, grid_size, largest_tile_m));
      field.synthesise(12.5);
      const double field_hs = 4.0 * std::sqrt(spatial_variance_m2(field));
      EXPECT_NEAR(field_hs, spectrum_hs, 0.03 * spectrum_hs) << spectrum->name() << " N=" << grid_size << " L=" << largest_tile_m;
      // Parseval: no wave has an opposite partner (pairs are merged), so the frames' variance
      // is the components' sum a^2/2 to float round-off (1e-4).
      EXPECT_NEAR(field_hs, field.significant_wave_height_m(), 1e-4 * spectrum_hs) << spectrum->name();
    }
  }
}

TEST(DeepWaterField, CascadesPartitionTheBandWithoutDoubleCounting) {
  // Adjacent bands touch and do not overlap, and the cascades' variances add up to the
  // spectrum's variance over the union of the bands (0.5 %: the band edge clipped on 8 x 8
  // sub-cells of the coarse lattice).
  auto spectrum = std::make_shared<UnifiedSpectrum>(12.8, 1.0, 0.0);
  const double peak_wavelength_m = 2.0 * std::numbers::pi / spectrum->peak_wavenumber_rad_m();
  DeepWaterField field(specification_for(spectrum, 64, 10.0 * peak_wavelength_m));
  double cascades_variance = 0.0;
  for (int c = 0; c < field.cascade_count(); ++c) {
    if (c > 0) {
      EXPECT_EQ(field.band(c).min_wavenumber_rad_m, field.band(c - 1).max_wavenumber_rad_m);
    }
    cascades_variance += field.cascade_variance_m2(c);
  }
  const double band_variance = spectrum->moment_between(1e-9, field.band(field.cascade_count() - 1).max_wavenumber_rad_m);
  EXPECT_NEAR(cascades_variance, band_variance, 5e-3 * band_variance);
  // The slope variance beyond the last band is what the lighting adds (> 0 for the unified
  // spectrum's capillary tail), and it is the spectrum's k^2 moment there.
  EXPECT_GT(field.unresolved_slope_variance(), 0.0);
}

TEST(DeepWaterField, LoopsExactly) {
  // field(t + T_loop) == field(t) to 1e-5 m (issue 5): every w_k is a whole harmonic of 2 pi / T
  // and w t is reduced modulo the loop in double before the float FFT. Deep and finite depth.
  for (double depth_m : {0.0, 15.0}) {
    DeepWaterSpecification spec = specification_for(std::make_shared<PmIttcSpectrum>(10.0, 0.0), 32, 400.0, 3);
    spec.still_water_depth_m = depth_m;
    spec.loop_period_s = 120.0;
    DeepWaterField field(spec);
    for (double t : {0.0, 31.7}) {
      field.synthesise(t);
      std::vector<std::vector<float>> first;
      for (int c = 0; c < field.cascade_count(); ++c) {
        first.push_back(field.frame(c).surface_elevation_m);
        first.push_back(field.frame(c).displacement_x_m);
      }
      field.synthesise(t + 3.0 * spec.loop_period_s);
      for (int c = 0; c < field.cascade_count(); ++c)
        for (std::size_t i = 0; i < first[2 * c].size(); ++i) {
          ASSERT_NEAR(field.frame(c).surface_elevation_m[i], first[2 * c][i], 1e-5);
          ASSERT_NEAR(field.frame(c).displacement_x_m[i], first[2 * c + 1][i], 1e-5);
        }
    }
    // ... and not trivially: half a loop later the sea is different.
    field.synthesise(0.0);
    const float at_start = field.frame(0).surface_elevation_m[100];
    field.synthesise(0.5 * spec.loop_period_s);
    EXPECT_GT(std::abs(field.frame(0).surface_elevation_m[100] - at_start), 1e-4);
  }
}

TEST(DeepWaterField, FftIsTheDirectSumOfItsComponentsAndTilesWrap) {
  // Every channel of the FFT frame equals the direct sum of wave_components() (the list the
  // harbour wave maker gets) at the lattice nodes, including the node one tile beyond the last
  // column and row, which is the first one again: the tile wraps seamlessly. Tolerance 2e-4 of
  // the channel's scale (float FFT of 32^2, float amplitudes).
  DeepWaterSpecification spec = specification_for(std::make_shared<UnifiedSpectrum>(9.0, 1.5, 0.7), 32, 150.0, 1);
  spec.still_water_depth_m = 12.0;
  DeepWaterField field(spec);
  const double t = 4.25;
  field.synthesise(t);
  const SeaState sea = field.wave_components();
  const DeepWaterFrame& frame = field.frame(0);
  const int n = frame.grid_size;
  const double step = frame.tile_length_m / n;
  const double eta_scale = 0.25 * field.significant_wave_height_m();
  const double slope_scale = std::sqrt(field.cascade_slope_variance(0));
  for (auto [row, column] : {std::pair{0, 0}, std::pair{3, 17}, std::pair{31, 31}, std::pair{32, 5}, std::pair{9, 32}}) {
    const DirectSum sum = direct_sum(sea, spec.still_water_depth_m, column * step, row * step, t);
    const std::size_t index = static_cast<std::size_t>(row % n) * n + column % n;
    EXPECT_NEAR(frame.surface_elevation_m[index], sum.eta, 2e-4 * eta_scale) << row << "," << column;
    EXPECT_NEAR(frame.displacement_x_m[index], sum.dx, 2e-4 * eta_scale);
    EXPECT_NEAR(frame.displacement_y_m[index], sum.dy, 2e-4 * eta_scale);
    EXPECT_NEAR(frame.slope_x[index], sum.sx, 2e-4 * slope_scale);
    EXPECT_NEAR(frame.slope_y[index], sum.sy, 2e-4 * slope_scale);
    EXPECT_NEAR(frame.displacement_xx[index], sum.dxx, 2e-4 * slope_scale);
    EXPECT_NEAR(frame.displacement_yy[index], sum.dyy, 2e-4 * slope_scale);
    EXPECT_NEAR(frame.displacement_xy[index], sum.dxy, 2e-4 * slope_scale);
  }
  // sample() is continuous across the tile edge (bilinear between the last column and the
  // first one again): the jump over 1 mm at the seam is as small as anywhere else.
  const double edge = frame.tile_length_m;
  EXPECT_NEAR(field.sample(edge - 5e-4, 17.0).surface_elevation_m, field.sample(edge + 5e-4, 17.0).surface_elevation_m,
              1e-3 * slope_scale * 10.0);
}

TEST(DeepWaterField, EveryComponentFollowsTheDispersionRelation) {
  // Each component's frequency must be w(k) of its lattice wavevector k = (n, m) 2 pi / L. From
  // the exported (w, direction) alone: the wavevector k(w) (cos th, sin th) from the dispersion
  // relation must land on the lattice (to 1e-9 of a lattice step), i.e. the phase speed w/k is
  // sqrt(g/k tanh(kd)) at the lattice k (deep and 10 m). With a loop, w is the nearest harmonic
  // of 2 pi / T: within pi / T of w(k_lattice), and a whole harmonic.
  for (double depth_m : {0.0, 10.0}) {
    for (double loop_s : {0.0, 200.0}) {
      DeepWaterSpecification spec = specification_for(std::make_shared<PmIttcSpectrum>(8.0, 0.0), 16, 300.0, 1);
      spec.still_water_depth_m = depth_m;
      spec.loop_period_s = loop_s;
      DeepWaterField field(spec);
      const SeaState sea = field.wave_components();
      ASSERT_GT(sea.components.size(), 40u);
      const double step = 2.0 * std::numbers::pi / 300.0;
      for (const WaveComponent& component : sea.components) {
        const double k = wavenumber_from_frequency(component.angular_frequency_rad_s, depth_m);
        const double n = k * std::cos(component.direction_rad) / step, m = k * std::sin(component.direction_rad) / step;
        const double lattice_k = std::hypot(std::round(n), std::round(m)) * step;
        if (loop_s == 0.0) {
          EXPECT_NEAR(n, std::round(n), 1e-9);
          EXPECT_NEAR(m, std::round(m), 1e-9);
          EXPECT_NEAR(component.angular_frequency_rad_s / lattice_k, phase_speed_m_s(lattice_k, depth_m),
                      1e-9 * phase_speed_m_s(lattice_k, depth_m));
        } else {
          EXPECT_LE(std::abs(component.angular_frequency_rad_s - frequency_from_wavenumber(lattice_k, depth_m)),
                    std::numbers::pi / loop_s + 1e-12);
          const double harmonics = component.angular_frequency_rad_s * loop_s / (2.0 * std::numbers::pi);
          EXPECT_NEAR(harmonics, std::round(harmonics), 1e-9);
        }
      }
    }
  }
}

TEST(DeepWaterField, JacobianIsOneOnAFlatSeaAndFoldsWhenChoppy) {
  // A flat sea (Phillips with A = 0): J = 1 exactly everywhere, no foam.
  DeepWaterField flat(specification_for(std::make_shared<PhillipsSpectrum>(0.0, 5.0, 0.0), 16, 100.0, 2));
  flat.synthesise(3.0);
  for (double x : {0.0, 13.3, 77.0}) {
    const SurfaceSample s = flat.sample(x, 0.5 * x);
    EXPECT_EQ(jacobian(s.displacement_xx, s.displacement_yy, s.displacement_xy, 1.0), 1.0);
  }
  // A steep sea with a strong choppiness (lambda = 3, Beaufort 9) folds: J < 0 somewhere, and
  // f_b > 0 exactly where J < J_b.
  auto steep = beaufort_preset(9).spectrum;
  DeepWaterSpecification spec = specification_for(steep, 64, 1.0);
  spec.tile_lengths_m = cascade_tile_lengths_for_m(*steep, 64, 4, 0.05);
  spec.choppiness = 3.0;
  DeepWaterField field(spec);
  field.synthesise(0.0);
  const FoamStatistics foam = foam_statistics(field, 20000);
  EXPECT_LT(foam.lowest_jacobian, 0.0);
  for (double jac : {-0.5, 0.0, 0.5, 0.556, 0.558, 1.0}) {
    EXPECT_EQ(foam_features(jac).breaking > 0.0, jac < kStokesBreakingJacobian);
    EXPECT_EQ(foam_features(jac).stretching, jac);
  }
}

TEST(DeepWaterField, FoamCoverageGrowsWithBeaufort) {
  // lambda = 1 (physical displacement), J_b at the Stokes limit, every preset (the seed's
  // Phillips/unified choice) resolved down to 5 cm waves: the coverage, averaged over two times
  // and 2 x 65536 low-discrepancy points, never falls from one force to the next by more than
  // three standard deviations of its counting noise, and rises overall (force 12 > 5 x force 4).
  std::vector<double> coverage;
  for (int force = 0; force <= 12; ++force) {
    const BeaufortPreset preset = beaufort_preset(force);
    if (!preset.spectrum) {
      coverage.push_back(0.0);  // calm: a flat sea, J = 1
      continue;
    }
    DeepWaterSpecification spec = specification_for(preset.spectrum, 64, 1.0);
    spec.tile_lengths_m = cascade_tile_lengths_for_m(*preset.spectrum, 64, 4, 0.05);
    DeepWaterField field(spec);
    double sum = 0.0;
    for (double t : {0.0, 7.0}) {
      field.synthesise(t);
      sum += foam_statistics(field, 65536).coverage;
    }
    coverage.push_back(0.5 * sum);
  }
  for (int force = 0; force <= 12; ++force) std::printf("foam coverage at Beaufort %d: %.4f %%\n", force, 100.0 * coverage[force]);
  for (int force = 1; force <= 12; ++force) {
    const double noise = 3.0 * std::sqrt(coverage[force - 1] / (2.0 * 65536.0));
    EXPECT_GE(coverage[force], coverage[force - 1] - noise) << "force " << force;
  }
  EXPECT_GT(coverage[12], 5.0 * coverage[4]);
  EXPECT_GT(coverage[1], 0.0);
}

TEST(BeaufortPresets, HeightsOfTable31) {
  // The preset's spectrum has the table's height (1 %: the bisection on Omega_c and the Phillips
  // closed form), and so does the synthesised field (3 %: the bound; the lattices lose
  // the variance beyond the 5 cm Nyquist wave, < 0.3 % here). Force 0 is flat.
  EXPECT_EQ(beaufort_preset(0).spectrum, nullptr);
  for (int force = 1; force <= 12; ++force) {
    const BeaufortPreset preset = beaufort_preset(force, 0.5);
    const double table_m = beaufort_table()[force].wave_height_m;
    EXPECT_NEAR(preset.spectrum->significant_wave_height_m(), table_m, 0.01 * table_m) << "force " << force;
    EXPECT_EQ(preset.spectrum->name(), force <= 4 ? "phillips" : "unified");
    if (force >= 5) {
      EXPECT_GE(preset.inverse_wave_age, 0.84);
      EXPECT_LE(preset.inverse_wave_age, 5.0);
      EXPECT_TRUE(preset.note.empty()) << preset.note;
    }
    DeepWaterSpecification spec;
    spec.spectrum = preset.spectrum;
    spec.grid_size = 64;
    spec.tile_lengths_m = cascade_tile_lengths_for_m(*preset.spectrum, 64, 4, 0.05);
    const DeepWaterField field(spec);
    EXPECT_NEAR(field.significant_wave_height_m(), table_m, 0.03 * table_m) << "force " << force;
  }
  // The choice is overridable.
  EXPECT_EQ(beaufort_preset(3, 0.0, BeaufortSpectrum::kUnified).spectrum->name(), "unified");
  EXPECT_EQ(beaufort_preset(9, 0.0, BeaufortSpectrum::kPhillips).spectrum->name(), "phillips");
  EXPECT_THROW(beaufort_preset(13), nearshore::Error);
}

TEST(DeepWaterField, TurbulentFoamDecays) {
  // eq. (3.46) as a recursion: with no new breaking the trail decays as exp(-t / tau).
  double f = turbulent_foam(0.0, 1.0, 0.1, 2.0);
  EXPECT_DOUBLE_EQ(f, 1.0);
  for (int i = 0; i < 20; ++i) f = turbulent_foam(f, 0.0, 0.1, 2.0);
  EXPECT_NEAR(f, std::exp(-1.0), 1e-12);
}

TEST(DeepWaterField, DescriptionAndCoefficientFiles) {
  // What a bake records of its field (bake/deep_water_record.hpp, sequence/deep_water_section.hpp):
  // the section survives its JSON round trip, and every coefficient file reads back to the field's
  // own lattice coefficients.
  DeepWaterSpecification spec = specification_for(std::make_shared<PmIttcSpectrum>(10.0, 0.2), 16, 400.0, 2);
  spec.loop_period_s = 300.0;
  DeepWaterField field(spec);
  const auto folder = std::filesystem::path(NEARSHORE_BINARY_DIR) / "tests" / "ocean" / "coefficients";
  std::filesystem::remove_all(folder);
  sequence::DeepWaterSection section = bake::describe_deep_water_field(field);
  bake::write_deep_water_coefficient_files(field, folder, section);
  const nlohmann::json description = sequence::deep_water_section_to_json(section);
  EXPECT_EQ(description["loop_period_s"], 300.0);
  EXPECT_EQ(description["seed"], 7u);
  EXPECT_EQ(description["spectrum"]["name"], "pm-ittc");
  const sequence::DeepWaterSection parsed = sequence::parse_deep_water_section(description, "test manifest");
  EXPECT_EQ(sequence::deep_water_section_to_json(parsed), description);
  ASSERT_EQ(parsed.cascades.size(), 2u);
  for (int c = 0; c < 2; ++c) {
    ASSERT_TRUE(parsed.cascades[c].coefficients.has_value());
    const auto file = folder / parsed.cascades[c].coefficients->file;
    EXPECT_EQ(std::filesystem::file_size(file), 32u + 16u * 16u * 16u);  // header + N^2 records
    std::ifstream in(file, std::ios::binary);
    char magic[8];
    in.read(magic, 8);
    EXPECT_EQ(std::string(magic, 8), "NSDWCOEF");
    const sequence::DeepWaterCoefficients read = sequence::read_deep_water_coefficients(file);
    const CascadeLattice lattice = field.lattice(c);
    ASSERT_EQ(read.amplitude_m.size(), lattice.amplitude_m.size());
    for (std::size_t k = 0; k < read.amplitude_m.size(); ++k) {
      EXPECT_EQ(read.amplitude_m[k], lattice.amplitude_m[k]);
      EXPECT_EQ(read.phase_rad[k], static_cast<float>(lattice.phase_rad[k]));
      EXPECT_EQ(read.harmonic[k], lattice.harmonic[k]);
    }
  }
  nlohmann::json newer = description;
  newer["format"] = "nearshore deep water 2";
  EXPECT_THROW(sequence::parse_deep_water_section(newer, "test manifest"), nearshore::Error);
}

TEST(DeepWaterField, BadSpecificationsNameTheFix) {
  auto spectrum = std::make_shared<PmIttcSpectrum>(10.0, 0.0);
  DeepWaterSpecification spec = specification_for(spectrum, 48, 100.0, 2);
  EXPECT_THROW(DeepWaterField{spec}, nearshore::Error);  // not a power of two
  spec = specification_for(spectrum, 32, 100.0, 2);
  spec.tile_lengths_m = {100.0, 200.0};
  EXPECT_THROW(DeepWaterField{spec}, nearshore::Error);  // not decreasing
  spec = specification_for(nullptr, 32, 100.0, 2);
  EXPECT_THROW(DeepWaterField{spec}, nearshore::Error);
  try {
    DeepWaterSpecification bad = specification_for(spectrum, 32, 100.0, 2);
    bad.choppiness = -1.0;
    DeepWaterField field(bad);
    FAIL();
  } catch (const nearshore::Error& error) {
    EXPECT_NE(std::string(error.what()).find("choppiness"), std::string::npos);
  }
}

TEST(DeepWaterTiles, TileSetIsASequenceOfTheCascadeOverOneLoop) {
  // One cascade over one 20 s loop in 8 frames, float channels: frame i holds the field at
  // i T / 8 (frame 4 = the field at 10 s, to 1e-6 m: float storage), the manifest says it loops
  // and carries the deep_water description. A field that does not loop, or a cascade that does
  // not exist, is an error.
  DeepWaterSpecification spec = specification_for(std::make_shared<PmIttcSpectrum>(6.0, 0.0), 16, 80.0, 2);
  spec.loop_period_s = 20.0;
  DeepWaterField field(spec);
  const auto folder = std::filesystem::path(NEARSHORE_BINARY_DIR) / "tests" / "deepwater" / "tile_set";
  std::filesystem::remove_all(folder);
  nearshore::sequence::FrameEncoding encoding;
  encoding.surface_elevation = nearshore::sequence::Precision::kFloat;
  encoding.flux = nearshore::sequence::Precision::kFloat;
  const TileSetSummary summary = write_deep_water_tile_set(field, 1, 8, folder, encoding);
  EXPECT_EQ(summary.frame_count, 8);
  EXPECT_DOUBLE_EQ(summary.frame_interval_s, 2.5);
  EXPECT_GT(summary.frame_bytes, 0u);
  const nearshore::sequence::SequenceReader reader(folder);
  EXPECT_EQ(reader.frame_count(), 8);
  EXPECT_DOUBLE_EQ(reader.manifest().loop_period_s, 20.0);
  ASSERT_TRUE(reader.manifest().deep_water.has_value());
  EXPECT_EQ(reader.manifest().deep_water->tile_set_cascade, 1);
  EXPECT_EQ(reader.geometry().columns, 16);
  EXPECT_DOUBLE_EQ(reader.geometry().spacing_m, 20.0 / 16.0);
  const auto frame = reader.read_frame(4, nearshore::sequence::ChannelSelection::all(), nearshore::sequence::Verify::kYes);
  field.synthesise(10.0);
  const auto& expected = field.frame(1).surface_elevation_m;
  for (std::size_t i = 0; i < expected.size(); ++i) ASSERT_NEAR(frame.surface_elevation_m.values()[i], expected[i], 1e-6);
  spec.loop_period_s = 0.0;
  DeepWaterField not_looping(spec);
  EXPECT_THROW(write_deep_water_tile_set(not_looping, 0, 8, folder / "x"), nearshore::Error);
  EXPECT_THROW(write_deep_water_tile_set(field, 5, 8, folder / "y"), nearshore::Error);
}
