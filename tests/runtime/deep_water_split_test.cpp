// The split drawn (issue 14 item 1, runtime half; docs/runtime.md "The split"): a real small bake
// whose irregular sea is partly too short for its cells leaves those components to the FFT
// deep-water layer, and the runtime draws them inside the harbour rectangle on top of the frames,
// band-limited so that nothing is counted twice.
#include <bit>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <numbers>

#include <gtest/gtest.h>

#include "nearshore/bake/bake_case.hpp"
#include "nearshore/bake/bake_run.hpp"
#include "nearshore/core/progress.hpp"
#include "nearshore/runtime/deep_water_source.hpp"
#include "nearshore/runtime/streaming_engine.hpp"
#include "nearshore/runtime/surface_sampler.hpp"
#include "runtime_test_support.hpp"

namespace nearshore::runtime {
namespace {
using namespace testing;
using namespace std::chrono_literals;

// A 12 m x 4 m basin, 0.5 m deep, on 0.2 m cells; a JONSWAP sea (Hs 4 cm, Tp 1.2 s, s = 20) from
// the west. Eight cells per wavelength carry waves down to 1.6 m, about 0.97 Hz at 0.5 m: the
// spectrum's peak (0.83 Hz) is baked, its upper part (about half the variance) is left to the
// [deep_water] field, which shares the maker's spectrum, spreading and seed. The field's two
// cascades (48 m and 12 m tiles, 128^2) resolve waves down to 0.19 m; the split (k about 3.9
// rad/m) falls in the 12 m tile's band, whose lattice step is 0.52 rad/m: the lattice gives each
// cell's variance to the side of its centre, so the cut is only as sharp as that step (a 6 m tile
// puts the layer's Hs 6 % off the record, this one 0.5 %). Frames every 0.25 s over 1 s.
const char* const kSplitCase = R"(title = "runtime split basin"
[bathymetry]
kind = "profile"
length_m = 12.0
width_m = 4.0
spacing_m = 0.2
profile = [[0.0, 0.5], [12.0, 0.5]]
[time]
duration_s = 2.0
spin_up_s = 1.0
output_interval_s = 0.25
courant_number = 0.5
[wave_maker]
kind = "irregular"
facing = "west"
source_line_m = 2.0
spectrum = "jonswap"
significant_height_m = 0.04
peak_period_s = 1.2
spreading_s = 20.0
frequency_count = 24
direction_count = 8
seed = 3
[deep_water]
grid_size = 128
tile_lengths_m = [48.0, 12.0]
[[sponges]]
side = "east"
width_m = 2.0
)";

struct SplitBake {
  fs::path sequence;
  std::unique_ptr<ocean::DeepWaterField> field;  // the bake's own, from its case
  std::vector<ocean::LatticeWave> carried;       // with drive_wave_maker: the field's waves the maker made
};

// Baked in the test's own scratch folder (about a second): ctest runs each test as a process of
// its own, possibly two at once, so a folder shared between tests would be written twice at once.
SplitBake split_bake(const std::string& deep_water_extra = {}) {
  ProgressBar::set_quiet(true);
  const fs::path folder = scratch_folder();
  std::string text = kSplitCase;
  const std::string section = "[deep_water]\n";
  text.insert(text.find(section) + section.size(), deep_water_extra);
  std::ofstream(folder / "case.toml") << text;
  const bake::BakeCase c = bake::read_bake_case(folder / "case.toml");
  bake::BakeOptions options;
  options.output_folder = folder / "sequence";
  bake::run_bake(c, options);
  SplitBake baked{options.output_folder, std::make_unique<ocean::DeepWaterField>(*c.deep_water), {}};
  if (c.deep_water_maker) baked.carried = c.deep_water_maker->carried;
  return baked;
}

// Formula 2 of surface_sampler.hpp for one periodic tile (nodes at i L / N), bilinear.
double tile_bilinear(const std::vector<float>& f, int n, double tile_m, double x_m, double y_m) {
  const auto axis = [&](double p, int& lo, int& hi, double& a) {
    double u = p / tile_m;
    u = (u - std::floor(u)) * n;
    lo = std::min(static_cast<int>(u), n - 1);
    a = u - lo;
    hi = (lo + 1) % n;
  };
  int i0 = 0, i1 = 0, j0 = 0, j1 = 0;
  double a = 0.0, b = 0.0;
  axis(x_m, i0, i1, a);
  axis(y_m, j0, j1, b);
  const auto at = [&](int i, int j) { return double(f[std::size_t(j) * std::size_t(n) + std::size_t(i)]); };
  return (1 - b) * ((1 - a) * at(i0, j0) + a * at(i1, j0)) + b * ((1 - a) * at(i0, j1) + a * at(i1, j1));
}
double slope_of(const ocean::DeepWaterFrame& frame, double x_m, double y_m, bool along_x) {
  return tile_bilinear(along_x ? frame.slope_x : frame.slope_y, frame.grid_size, frame.tile_length_m, x_m, y_m);
}

StreamingOptions split_options() {
  StreamingOptions options;
  options.ring_capacity = 3;
  options.deep_water_ring_capacity = 3;
  return options;
}

TEST(RuntimeDeepWaterSplit, TheInsideLayerHoldsTheLeftComponentsHsAndNoneOfTheBakesBand) {
  const SplitBake bake = split_bake();
  StreamingEngine engine(bake.sequence, split_options());
  const std::optional<SpectrumSplitRecord>& split = engine.spectrum_split();
  ASSERT_TRUE(split.has_value()) << "the case is meant to split its spectrum";
  ASSERT_TRUE(split->deep_water_layer_present);
  ASSERT_TRUE(engine.deep_water_is_bakes());
  const std::shared_ptr<const DeepWaterInsideLayer> layer = engine.deep_water_inside_layer();
  ASSERT_TRUE(layer);
  constexpr double kHz = 0.5 / std::numbers::pi;

  // The split lies between the bake's band and the left components (the cells' common edge).
  EXPECT_GT(split->split_frequency_hz, split->bake_max_frequency_hz);
  EXPECT_NEAR(layer->split_angular_frequency_rad_s * kHz, split->split_frequency_hz, 1e-12);

  // Hs: the layer is the field's lattice waves above the split, the record the builder's (w,
  // theta) cells above it: two quadratures of the same spectrum band. The field's lattice holds
  // any spectrum's Hs within 3 % (tests/ocean DeepWaterField.HsIsTheSpectrums...); the builder
  // keeps the band holding 99.5 % of m0 and so leaves out at most 0.4 % of the variance above
  // it (0.2 % of Hs), which the lattice holds; and the cut is as sharp as the lattice step (see
  // the case). So: within 3 % (measured 0.5 %: 0.02237 m against 0.02226 m).
  const double recorded_m = split->deep_water_significant_wave_height_m;
  EXPECT_NEAR(layer->significant_wave_height_m(), recorded_m, 0.03 * recorded_m)
      << "inside layer Hs " << layer->significant_wave_height_m() << " m, manifest's deep-water Hs " << recorded_m << " m";
  std::printf("split at %.4f Hz (bake band %.4f-%.4f Hz): inside layer Hs %.5f m (%d components), manifest's deep-water Hs %.5f m\n",
              split->split_frequency_hz, split->bake_min_frequency_hz, split->bake_max_frequency_hz,
              layer->significant_wave_height_m(), layer->component_count, recorded_m);
  // And the budget closes: Hs_total^2 = Hs_bake^2 + Hs_deep^2 (variances add).
  EXPECT_NEAR(std::hypot(split->bake_significant_wave_height_m, recorded_m), split->total_significant_wave_height_m, 1e-9);

  // The bake's band is absent: every component drawn inside lies above the split, and every
  // component the bake made lies at or below it.
  EXPECT_GT(layer->lowest_angular_frequency_rad_s * kHz, split->split_frequency_hz);
  for (const nlohmann::json& component : engine.manifest().wave_conditions["components"])
    EXPECT_LE(component["angular_frequency_rad_s"].get<double>() * kHz, split->split_frequency_hz);
  const ocean::RecordedDeepWater record = bake.field->record();
  double above_m2 = 0.0, below_m2 = 0.0;
  for (const ocean::RecordedCascade& cascade : record.cascades)
    for (std::size_t i = 0; i < cascade.amplitude_m.size(); ++i)
      (cascade.angular_frequency_rad_s[i] > layer->split_angular_frequency_rad_s * (1 + 1e-9) ? above_m2 : below_m2) +=
          0.5 * double(cascade.amplitude_m[i]) * cascade.amplitude_m[i];
  EXPECT_NEAR(layer->variance_m2, above_m2, 1e-9 * above_m2);
  EXPECT_GT(below_m2, 0.1 * above_m2) << "the field holds the bake's band too (drawn beyond the rectangle only)";
  // Each cascade is drawn inside whole (all its components above the split), band-limited (it
  // straddles the split: only what straddles is synthesised a second time) or not at all.
  std::size_t straddling = 0;
  for (std::size_t c = 0; c < record.cascades.size(); ++c) {
    int above = 0, below = 0;
    const ocean::RecordedCascade& cascade = record.cascades[c];
    for (std::size_t i = 0; i < cascade.amplitude_m.size(); ++i)
      if (cascade.amplitude_m[i] != 0.0f) (cascade.angular_frequency_rad_s[i] > layer->split_angular_frequency_rad_s ? above : below)++;
    const bool whole = (layer->whole_cascade_mask >> c) & 1u;
    const bool straddles = straddling < layer->straddling_cascades.size() && layer->straddling_cascades[straddling] == int(c);
    if (straddles) ++straddling;
    EXPECT_EQ(whole, above > 0 && below == 0) << "cascade " << c;
    EXPECT_EQ(straddles, above > 0 && below > 0) << "cascade " << c;
  }
  EXPECT_EQ(straddling, layer->straddling.cascades.size());
  EXPECT_GE(straddling, std::size_t{1}) << "the case's split falls inside a cascade's band";
  for (const ocean::RecordedCascade& cascade : layer->straddling.cascades)
    for (std::size_t i = 0; i < cascade.amplitude_m.size(); ++i) {
      if (cascade.amplitude_m[i] != 0.0f) {
        EXPECT_GT(cascade.angular_frequency_rad_s[i], layer->split_angular_frequency_rad_s);
      }
    }
}

TEST(RuntimeDeepWaterSplit, KeyframesCarryTheLayerAndTheQueriesDrawItInsideTheRectangle) {
  const SplitBake bake = split_bake();
  StreamingEngine engine(bake.sequence, split_options());
  const std::shared_ptr<const DeepWaterInsideLayer> layer = engine.deep_water_inside_layer();
  ASSERT_TRUE(layer);
  const SurfaceSnapshot snapshot = engine.snapshot_at(0.5);
  ASSERT_TRUE(snapshot.deep_from && snapshot.harbour_from);
  const DeepWaterKeyframe& keyframe = *snapshot.deep_from;
  EXPECT_EQ(keyframe.inside_cascade_mask, layer->whole_cascade_mask);
  ASSERT_EQ(keyframe.inside_cascades.size(), layer->straddling.cascades.size());

  // By Parseval each tile's mean square is its cascade's sum a^2/2 (to float round-off): the
  // frames drawn inside hold exactly the layer's variance, the split-off Hs.
  double drawn_m2 = 0.0;
  const auto mean_square = [](const ocean::DeepWaterFrame& frame) {
    double sum = 0.0;
    for (float v : frame.surface_elevation_m) sum += double(v) * v;
    return sum / double(frame.surface_elevation_m.size());
  };
  for (std::size_t c = 0; c < keyframe.cascades.size(); ++c)
    if ((keyframe.inside_cascade_mask >> c) & 1u) drawn_m2 += mean_square(keyframe.cascades[c]);
  for (const ocean::DeepWaterFrame& frame : keyframe.inside_cascades) drawn_m2 += mean_square(frame);
  EXPECT_NEAR(drawn_m2, layer->variance_m2, 1e-4 * layer->variance_m2);

  const SurfaceSampler sampler(snapshot);
  ASSERT_TRUE(sampler.has_inside_layer());
  const HarbourSite& site = *snapshot.site;
  // Formula 3 of surface_sampler.hpp at lattice points: w (H + I) + (1 - w) D, across the
  // rectangle (full weight in the middle, the edge fades) and beyond it (the whole field).
  double inside_energy_m2 = 0.0;
  int inside_points = 0;
  for (double x = -1.0; x <= site.width_m + 1.0; x += 0.37)
    for (double y = -1.0; y <= site.height_m + 1.0; y += 0.29) {
      const double w = harbour_weight(site, x, y);
      const double expected = w * (sampler.harbour_elevation_m(x, y) + sampler.inside_elevation_m(x, y)) +
                              (1.0 - w) * sampler.deep_elevation_m(x, y);
      EXPECT_NEAR(sampler.elevation_m(x, y, ChoppyPoint::kLattice), expected, 1e-12) << x << ", " << y;
      const SurfaceState state = sampler.state(x, y, ChoppyPoint::kLattice);
      EXPECT_NEAR(state.surface_elevation_m, expected, 1e-12) << x << ", " << y;
      if (w == 1.0) {
        inside_energy_m2 += std::pow(sampler.inside_elevation_m(x, y), 2);
        ++inside_points;
      }
    }
  ASSERT_GT(inside_points, 50);
  // The short waves are there inside: their mean square over the interior is of the layer's
  // variance (a 12 m x 4 m patch holds a few dozen of their wavelengths: within a factor 2).
  EXPECT_GT(inside_energy_m2 / inside_points, 0.5 * layer->variance_m2);
  EXPECT_LT(inside_energy_m2 / inside_points, 2.0 * layer->variance_m2);

  // A displaced query inside the full-weight box is the lattice query (the layer is drawn
  // without choppy displacement there), and the slope adds the layer's.
  const double x = 0.5 * site.width_m + 0.5, y = 0.5 * site.height_m;
  ASSERT_EQ(harbour_weight(site, x, y), 1.0);
  EXPECT_NEAR(sampler.elevation_m(x, y), sampler.harbour_elevation_m(x, y) + sampler.inside_elevation_m(x, y), 1e-12);
  DeepWaterKeyframe without = keyframe;
  without.inside_cascade_mask = 0;
  without.inside_cascades.clear();
  SurfaceSnapshot bare = snapshot;
  bare.deep_from = std::make_shared<const DeepWaterKeyframe>(without);
  bare.deep_to = bare.deep_from;
  bare.deep_fraction = 0.0;
  SurfaceSnapshot one = snapshot;
  one.deep_to = one.deep_from;
  one.deep_fraction = 0.0;
  const SurfaceState a = SurfaceSampler(one).state(x, y), b = SurfaceSampler(bare).state(x, y);
  EXPECT_FALSE(SurfaceSampler(bare).has_inside_layer());
  double slope_x = 0.0, slope_y = 0.0;
  for (std::size_t c = 0; c < keyframe.cascades.size(); ++c)
    if ((keyframe.inside_cascade_mask >> c) & 1u) {
      slope_x += slope_of(keyframe.cascades[c], x, y, true);
      slope_y += slope_of(keyframe.cascades[c], x, y, false);
    }
  for (const ocean::DeepWaterFrame& frame : keyframe.inside_cascades) {
    slope_x += slope_of(frame, x, y, true);
    slope_y += slope_of(frame, x, y, false);
  }
  EXPECT_NEAR(a.slope_x - b.slope_x, slope_x, 1e-9);
  EXPECT_NEAR(a.slope_y - b.slope_y, slope_y, 1e-9);
  EXPECT_NEAR(a.surface_elevation_m - b.surface_elevation_m, SurfaceSampler(one).inside_elevation_m(x, y), 1e-12);
}

TEST(RuntimeDeepWaterSplit, AFieldThatDrivesTheMakerIsDrawnInsideAboveTheWavesTheMakerMade) {
  // drive_wave_maker = true: the maker makes the field's own lattice waves up to the band's top,
  // so the layer must start exactly there (the record's split_frequency_hz is that top), and the
  // baked waves and the layer are then one set of waves, split by frequency.
  const SplitBake bake = split_bake("drive_wave_maker = true\n");
  ASSERT_FALSE(bake.carried.empty());
  StreamingEngine engine(bake.sequence, split_options());
  ASSERT_TRUE(engine.spectrum_split().has_value());
  const std::shared_ptr<const DeepWaterInsideLayer> layer = engine.deep_water_inside_layer();
  ASSERT_TRUE(layer);
  constexpr double kHz = 0.5 / std::numbers::pi;
  double top_rad_s = 0.0;
  for (const ocean::LatticeWave& wave : bake.carried) top_rad_s = std::max(top_rad_s, wave.wave.angular_frequency_rad_s);
  // The split is the top of the maker's band (the builder's highest component, which the lattice
  // need not hold exactly): at or above every carried wave.
  EXPECT_NEAR(layer->split_angular_frequency_rad_s * kHz, engine.spectrum_split()->bake_max_frequency_hz, 1e-12);
  EXPECT_GE(layer->split_angular_frequency_rad_s, top_rad_s);
  EXPECT_GT(layer->lowest_angular_frequency_rad_s, top_rad_s);
  // No wave the maker made is drawn inside: at each carried wavevector the layer's amplitude is 0
  // (a lattice index is its wavevector: n = k L / 2 pi, negative indices wrapped).
  const ocean::RecordedDeepWater record = bake.field->record();
  int checked = 0;
  for (const ocean::LatticeWave& wave : bake.carried)
    for (std::size_t c = 0; c < record.cascades.size(); ++c) {
      const ocean::RecordedCascade& cascade = record.cascades[c];
      const int n = cascade.grid_size;
      const long column = std::lround(wave.wavenumber_x_rad_m * cascade.tile_length_m / (2 * std::numbers::pi));
      const long row = std::lround(wave.wavenumber_y_rad_m * cascade.tile_length_m / (2 * std::numbers::pi));
      if (std::abs(column) >= n / 2 || std::abs(row) >= n / 2) continue;
      const std::size_t i = std::size_t((row + n) % n) * std::size_t(n) + std::size_t((column + n) % n);
      if (cascade.amplitude_m[i] != static_cast<float>(wave.wave.amplitude_m)) continue;  // another cascade's
      ++checked;
      const bool drawn_whole = (layer->whole_cascade_mask >> c) & 1u;
      EXPECT_FALSE(drawn_whole) << "cascade " << c << " holds a baked wave";
      for (std::size_t s = 0; s < layer->straddling_cascades.size(); ++s)
        if (layer->straddling_cascades[s] == int(c)) {
          EXPECT_EQ(layer->straddling.cascades[s].amplitude_m[i], 0.0f);
        }
    }
  EXPECT_EQ(checked, static_cast<int>(bake.carried.size()));
  // Hs: the layer is the field above the split, exactly. The record's deep-water Hs is the
  // builder's left cells, which start half a cell higher (its cell edge): driven, the lattice
  // waves between the maker's top and that edge are the layer's too, so the layer is higher than
  // the record (measured 0.02543 m against 0.02226 m; docs/runtime.md "The split").
  double above_m2 = 0.0;
  for (const ocean::RecordedCascade& cascade : record.cascades)
    for (std::size_t i = 0; i < cascade.amplitude_m.size(); ++i)
      if (cascade.angular_frequency_rad_s[i] > layer->split_angular_frequency_rad_s * (1 + 1e-9))
        above_m2 += 0.5 * double(cascade.amplitude_m[i]) * cascade.amplitude_m[i];
  EXPECT_NEAR(layer->variance_m2, above_m2, 1e-9 * above_m2);
  const double recorded_m = engine.spectrum_split()->deep_water_significant_wave_height_m;
  std::printf("driven: split at %.4f Hz, inside layer Hs %.5f m, manifest's deep-water Hs %.5f m\n",
              layer->split_angular_frequency_rad_s * kHz, layer->significant_wave_height_m(), recorded_m);
  EXPECT_GE(layer->significant_wave_height_m(), recorded_m);
}

}  // namespace
}  // namespace nearshore::runtime
