// [deep_water] in a bake (issue 5: coherence with the harbour, output): the case keys, the wave
// maker made of the field's own waves, the coefficient files and manifest entry the runtime reads,
// and the summary. The physics of the coupling (baked gauges against the field across the blending
// zone) is measured in tests/deepwater/coherence_test.cpp.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>
#include <span>

#include <gtest/gtest.h>

#include "bake_test_support.hpp"
#include "nearshore/bake/bake_case.hpp"
#include "nearshore/bake/bake_run.hpp"
#include "nearshore/ocean/deep_water.hpp"
#include "nearshore/bake/deep_water_coupling.hpp"
#include "nearshore/core/error.hpp"
#include "nearshore/core/harbour_grid.hpp"
#include "nearshore/core/progress.hpp"
#include "nearshore/sequence/checksum.hpp"
#include "nearshore/sequence/sequence_reader.hpp"

namespace nearshore::bake {

using namespace nearshore::ocean;
using namespace nearshore::boussinesq;
namespace {
namespace fs = std::filesystem;
using testing::expect_case_error;
using testing::scratch_folder;
using testing::small_flume_case;
using testing::write_text;

// The small flume (12 m x 0.6 m, 0.5 m deep, waves from the west) with its regular wave maker
// replaced by `maker` (the keys after facing and source_line_m) and `deep` appended.
std::string flume_case(const std::string& maker, const std::string& deep, double duration_s = 4.0) {
  std::string text = small_flume_case(duration_s);
  const std::string regular =
      "kind = \"regular\"\nfacing = \"west\"\nsource_line_m = 3.0\nheight_m = 0.02\nperiod_s = 2.0\n";
  text.replace(text.find(regular), regular.size(), "facing = \"west\"\nsource_line_m = 3.0\n" + maker);
  return text + deep;
}

// A field of its own, made by the maker: JONSWAP Hs 2 cm, Tp 1.5 s, on a 32 s loop.
const std::string kDeepWaterMaker = "kind = \"deep_water\"\nloop_period_s = 32.0\n";
const std::string kDeepWaterField =
    "[deep_water]\nspectrum = \"jonswap\"\nsignificant_height_m = 0.02\npeak_period_s = 1.5\nspreading_s = "
    "10.0\n"
    "grid_size = 64\ncascade_count = 1\nseed = 5\n";
// The irregular maker whose sea [deep_water] shares.
const std::string kIrregularMaker =
    "kind = \"irregular\"\nsignificant_height_m = 0.02\npeak_period_s = 1.5\nfrequency_count = 16\nseed = "
    "99\n"
    "loop_period_s = 32.0\nspreading_s = 10.0\ndirection_count = 8\nmin_frequency_hz = 0.3\nmax_frequency_hz "
    "= 1.2\n";

// eta at (x, y, t) from the coefficient files alone, as a runtime that reads them would: every
// record a cos(k . x - w t + phi), k from its FFT indices, w from its harmonic when the field loops.
double elevation_from_coefficient_files(const fs::path& folder, const sequence::DeepWaterSection& deep_water,
                                        double x_m, double y_m, double t_s) {
  double eta = 0.0;
  for (const sequence::DeepWaterCascadeRecord& cascade : deep_water.cascades) {
    const sequence::DeepWaterCoefficients c = sequence::read_deep_water_coefficients(folder / cascade.coefficients->file);
    const int n = c.grid_size;
    const double dk = 2 * std::numbers::pi / c.tile_length_m;
    for (int row = 0; row < n; ++row)
      for (int column = 0; column < n; ++column) {
        const std::size_t i = static_cast<std::size_t>(row) * n + column;
        const double kx = (column <= n / 2 ? column : column - n) * dk,
                     ky = (row <= n / 2 ? row : row - n) * dk;
        const double w =
            c.loop_period_s > 0 ? c.harmonic[i] * 2 * std::numbers::pi / c.loop_period_s : c.angular_frequency_rad_s[i];
        eta += c.amplitude_m[i] * std::cos(kx * x_m + ky * y_m - w * t_s + c.phase_rad[i]);
      }
  }
  return eta;
}

class BakeDeepWater : public ::testing::Test {
 protected:
  void SetUp() override { ProgressBar::set_quiet(true); }
};

// The irregular maker's sea, carried beyond the domain: coefficients beside the frames (checksummed,
// and readable back into the same field), the description and its placement in the manifest, the
// same Hs as the maker's spectrum (issue 5: within 3 % of the spectrum's integral), a tile set.
TEST_F(BakeDeepWater, IrregularMakerSharesItsSeaWithTheFieldBeyondTheDomain) {
  const auto folder = scratch_folder();
  const BakeCase c = read_bake_case(
      write_text(folder / "case.toml",
                 flume_case(kIrregularMaker,
                            "[deep_water]\ngrid_size = 64\ncascade_count = 2\nshortest_wavelength_m = 0.05\n"
                            "tile_set_frame_interval_s = 4.0\ntile_set_cascade = 1\n")));
  ASSERT_TRUE(c.deep_water.has_value());
  EXPECT_FALSE(c.deep_water_maker.has_value());              // the maker keeps its own discretisation
  EXPECT_DOUBLE_EQ(c.deep_water->still_water_depth_m, 0.5);  // the flume's depth at the source line
  BakeOptions options;
  options.output_folder = folder / "out";
  const BakeSummary summary = run_bake(c, options);
  const sequence::SequenceReader reader(options.output_folder);
  ASSERT_TRUE(reader.manifest().deep_water.has_value());
  const sequence::DeepWaterSection& deep_section = *reader.manifest().deep_water;
  // The section as written in manifest.json (its keys are sequence/'s; the test reads them as a user would).
  const nlohmann::json deep = sequence::deep_water_section_to_json(deep_section);
  ASSERT_TRUE(deep.is_object());
  EXPECT_EQ(deep["seed"], 99u);
  EXPECT_DOUBLE_EQ(deep["loop_period_s"].get<double>(), 32.0);
  EXPECT_NEAR(deep["significant_wave_height_m"].get<double>(), 0.02, 0.03 * 0.02);
  EXPECT_EQ(deep["coupling"]["drives_wave_maker"], false);
  EXPECT_DOUBLE_EQ(deep["coupling"]["origin_x_m"].get<double>(), c.harbour.geometry.origin_x_m);
  EXPECT_FALSE(deep["coupling"].contains("blending"));  // not the same waves: nothing to blend seamlessly
  ASSERT_EQ(deep["cascades"].size(), 2u);
  for (const nlohmann::json& cascade : deep["cascades"]) {
    const std::string bytes =
        sequence::read_file_bytes(options.output_folder / cascade["coefficients_file"].get<std::string>());
    EXPECT_EQ(bytes.size(), cascade["coefficients_bytes"].get<std::size_t>());
    EXPECT_EQ(sequence::checksum_text(std::as_bytes(std::span(bytes.data(), bytes.size()))),
              cascade["coefficients_checksum"].get<std::string>());
  }
  EXPECT_NO_THROW(reader.verify_checksums());
  // Read back, the files are the field: eta from them equals the field's own sum (float records).
  const DeepWaterField field(*c.deep_water);
  for (const double t : {0.0, 7.3, 31.9})
    EXPECT_NEAR(elevation_from_coefficient_files(options.output_folder, deep_section, 1.7, 0.2, t),
                surface_elevation_m(field.lattice_waves(), 1.7, 0.2, t), 1e-5 * 0.02);
  EXPECT_EQ(summary.deep_water["cascades"], 2);
  EXPECT_EQ(summary.deep_water["drives_wave_maker"], false);
  // The optional baked tile set: cascade 1 over the 32 s loop every 4 s, itself a sequence.
  const sequence::SequenceReader tiles(options.output_folder / "deep_water_tiles");
  EXPECT_EQ(tiles.frame_count(), 8);
  EXPECT_EQ(deep["tile_set"]["frames"], 8);
  EXPECT_EQ(tiles.manifest().deep_water->tile_set_cascade, 1);
  // A corrupt coefficient file is caught by the same verification as the frames, and by the reader.
  const fs::path coefficients =
      options.output_folder / deep["cascades"][1]["coefficients_file"].get<std::string>();
  std::string bytes = sequence::read_file_bytes(coefficients);
  bytes[bytes.size() / 2] = static_cast<char>(bytes[bytes.size() / 2] ^ 0x40);
  std::ofstream(coefficients, std::ios::binary) << bytes;
  EXPECT_THROW(reader.verify_checksums(), Error);
  std::ofstream(coefficients, std::ios::binary) << bytes.substr(0, 1000);
  try {
    sequence::read_deep_water_coefficients(coefficients);
    ADD_FAILURE() << "a truncated coefficient file was read";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("deep_water_cascade_1.bin"), std::string::npos) << error.what();
  }
}

// wave_maker.kind = "deep_water": a field of its own drives the maker; the manifest says where the
// field lies and where to blend, the summary how much of the field the maker carries.
TEST_F(BakeDeepWater, DeepWaterMakerBakeWritesTheFieldAndReportsTheVarianceItCarries) {
  const auto folder = scratch_folder();
  const BakeCase c =
      read_bake_case(write_text(folder / "case.toml", flume_case(kDeepWaterMaker, kDeepWaterField)));
  ASSERT_TRUE(c.deep_water_maker.has_value());
  const CoupledWaveMaker& coupled = *c.deep_water_maker;
  EXPECT_EQ(c.wave_maker.kind, WaveMaker::Kind::kComponents);
  EXPECT_EQ(c.wave_maker.sea_state.seed, 5u);
  EXPECT_DOUBLE_EQ(c.wave_maker.sea_state.loop_period_s, 32.0);
  EXPECT_EQ(c.wave_maker.sea_state.components.size(), coupled.carried.size());
  EXPECT_GT(coupled.variance_fraction(), 0.5);
  EXPECT_LE(coupled.variance_fraction(), 1.0);
  EXPECT_EQ(c.wave_conditions["driven_by_deep_water"], true);
  // The blending zone: from the inland edge of the source strip (3 / sqrt(20) peak wavelengths),
  // one peak wavelength wide, or down to half of it where the predicted mismatch would pass the
  // seam criterion; weight 0, then sin^2, then 1.
  const BlendingZone& zone = coupled.blending;
  const double peak_wavelength_m = zone.start_m * std::sqrt(20.0) / 3.0;
  EXPECT_EQ(zone.side, Side::kWest);
  EXPECT_DOUBLE_EQ(zone.source_line_m, 3.0);
  EXPECT_GT(peak_wavelength_m, 2.0);  // Tp = 1.5 s in 0.5 m of water: about 3 m
  EXPECT_LT(peak_wavelength_m, 4.0);
  EXPECT_LE(zone.width_m, peak_wavelength_m * (1 + 1e-12));
  EXPECT_GE(zone.width_m, 0.5 * peak_wavelength_m * (1 - 1e-12));
  EXPECT_DOUBLE_EQ(zone.predicted_relative_rms_end, coupled.relative_rms_drift(zone.start_m + zone.width_m));
  EXPECT_EQ(zone.seamless, zone.predicted_relative_rms_end <= kSeamlessRelativeRms);
  EXPECT_LT(zone.predicted_relative_rms_start, zone.predicted_relative_rms_end);
  EXPECT_DOUBLE_EQ(zone.distance_inland_m(3.0 + zone.start_m, 0.3), zone.start_m);
  EXPECT_EQ(zone.baked_weight(0.0), 0.0);
  EXPECT_EQ(zone.baked_weight(zone.start_m), 0.0);
  EXPECT_NEAR(zone.baked_weight(zone.start_m + 0.5 * zone.width_m), 0.5, 1e-12);
  EXPECT_EQ(zone.baked_weight(zone.start_m + zone.width_m), 1.0);

  BakeOptions options;
  options.output_folder = folder / "out";
  const BakeSummary summary = run_bake(c, options);
  const sequence::SequenceReader reader(options.output_folder);
  ASSERT_TRUE(reader.manifest().deep_water.has_value());
  const sequence::DeepWaterSection& deep_section = *reader.manifest().deep_water;
  // The section as written in manifest.json (its keys are sequence/'s; the test reads them as a user would).
  const nlohmann::json deep = sequence::deep_water_section_to_json(deep_section);
  ASSERT_TRUE(deep.is_object());
  EXPECT_EQ(deep["seed"], 5u);
  EXPECT_EQ(deep["spectrum"]["name"], "jonswap+cos2s");
  EXPECT_NEAR(deep["significant_wave_height_m"].get<double>(), 0.02, 0.03 * 0.02);
  const nlohmann::json& coupling = deep["coupling"];
  EXPECT_EQ(coupling["drives_wave_maker"], true);
  EXPECT_EQ(coupling["wave_maker"]["components"], coupled.carried.size());
  EXPECT_DOUBLE_EQ(coupling["wave_maker"]["variance_fraction"].get<double>(), coupled.variance_fraction());
  EXPECT_EQ(coupling["blending"]["side"], "west");
  EXPECT_DOUBLE_EQ(coupling["blending"]["start_m"].get<double>(), zone.start_m);
  EXPECT_NO_THROW(reader.verify_checksums());
  const DeepWaterField field(*c.deep_water);
  EXPECT_NEAR(elevation_from_coefficient_files(options.output_folder, deep_section, 5.0, 0.3, 12.0),
              surface_elevation_m(field.lattice_waves(), 5.0, 0.3, 12.0), 1e-5 * 0.02);
  // --json: the summary carries the same figures.
  const nlohmann::json json = summary.to_json();
  EXPECT_EQ(json["deep_water"]["drives_wave_maker"], true);
  EXPECT_DOUBLE_EQ(json["deep_water"]["variance_fraction"].get<double>(), coupled.variance_fraction());
  EXPECT_EQ(json["deep_water"]["wave_maker_components"], coupled.carried.size());
  EXPECT_NEAR(json["deep_water"]["carried_significant_wave_height_m"].get<double>(),
              std::sqrt(coupled.variance_fraction()) * deep["significant_wave_height_m"].get<double>(),
              1e-6 * 0.02);
}

// The Madsen & Sorensen wavenumber of docs/solver.md: w^2 = g d k^2 (1 + B (kd)^2) / (1 + (B + 1/3) (kd)^2).
double model_wavenumber(double w, double d, double B) {
  double k = w / std::sqrt(kGravity_m_s2 * d);
  for (int i = 0; i < 100; ++i) {
    const auto f = [&](double q) {
      return kGravity_m_s2 * d * q * q * (1 + B * q * q * d * d) / (1 + (B + 1.0 / 3.0) * q * q * d * d) -
             w * w;
    };
    const double h = 1e-7 * k;
    k -= f(k) * 2 * h / (f(k + h) - f(k - h));
  }
  return k;
}

// The conversion of deep_water_coupling.hpp on a grid in a UTM frame (origin 386 km E, 4306 km N)
// with oblique, looping waves from the west: every maker component, as the solver's source line
// makes it (phase referred to the projected frame's zero, model wavenumber at the line's depth), is
// the field's lattice wave (field frame: the grid's south-west corner) at every point of the line
// and every time; same amplitude and frequency, direction turned by a few degrees at most (Snell).
TEST_F(BakeDeepWater, MakerWavesAreTheFieldsOnTheSourceLineOfAUtmGrid) {
  const auto folder = scratch_folder();
  GridGeometry geometry;
  geometry.columns = 100;
  geometry.rows = 60;
  geometry.spacing_m = 4.0;
  geometry.origin_x_m = 386000.0;
  geometry.origin_y_m = 4306000.0;
  write_harbour_grid(folder / "depth.exr", HarbourGrid::open_water(geometry, 12.0f));
  const std::string text =
      "[bathymetry]\nkind = \"harbour_grid\"\nfile = \"depth.exr\"\n"
      "[time]\nduration_s = 60.0\noutput_interval_s = 10.0\n"
      "[wave_maker]\nkind = \"deep_water\"\nfacing = \"west\"\nsource_line_m = 60.0\nloop_period_s = 300.0\n"
      "[deep_water]\nspectrum = \"jonswap\"\nsignificant_height_m = 1.0\npeak_period_s = "
      "8.0\nmean_direction_deg = 20.0\n"
      "spreading_s = 20.0\ntile_lengths_m = [320.0]\ngrid_size = 32\nseed = 3\n";
  const BakeCase c = read_bake_case(write_text(folder / "case.toml", text));
  ASSERT_TRUE(c.deep_water_maker.has_value());
  const CoupledWaveMaker& coupled = *c.deep_water_maker;
  ASSERT_GT(coupled.carried.size(), 10u);
  const double d = source_line_depth_m(c.wave_maker, c.harbour);
  EXPECT_NEAR(d, 12.0, 1e-6);
  const double B = c.solver.dispersion_coefficient;
  const std::vector<LatticeWave> lattice = DeepWaterField(*c.deep_water).lattice_waves();
  double oblique = 0.0, largest_turn_rad = 0.0;
  for (std::size_t i = 0; i < coupled.carried.size(); ++i) {
    const WaveComponent& made = c.wave_maker.sea_state.components[i];
    const LatticeWave& wave = coupled.carried[i];
    // Snell across the change of dispersion relation: the model wavevector keeps the lattice's
    // component along the line (here y).
    const double model_k = model_wavenumber(made.angular_frequency_rad_s, d, B);
    EXPECT_NEAR(model_k * std::sin(made.direction_rad), wave.wavenumber_y_rad_m, 1e-9 * model_k);
    EXPECT_TRUE(std::any_of(lattice.begin(), lattice.end(), [&](const LatticeWave& l) {
      return l.wavenumber_x_rad_m == wave.wavenumber_x_rad_m &&
             l.wavenumber_y_rad_m == wave.wavenumber_y_rad_m && l.wave.phase_rad == wave.wave.phase_rad;
    }));
    EXPECT_EQ(made.amplitude_m, wave.wave.amplitude_m);
    EXPECT_EQ(made.angular_frequency_rad_s, wave.wave.angular_frequency_rad_s);
    EXPECT_GT(std::cos(made.direction_rad), 0.2);  // into the domain, within the source's 78 degrees
    largest_turn_rad =
        std::max(largest_turn_rad, std::abs(wrap_angle_rad(made.direction_rad - wave.wave.direction_rad)));
    oblique = std::max(oblique, std::abs(wave.wavenumber_y_rad_m));
    const double k = model_wavenumber(made.angular_frequency_rad_s, d, B);
    const double kx = k * std::cos(made.direction_rad), ky = k * std::sin(made.direction_rad);
    const double line_x_m = c.wave_maker.source_line_m;  // projected frame
    for (const double y_local_m : {0.0, 2.0, 117.0, 238.0})
      for (const double t_s : {0.0, 41.3, 299.9}) {
        const double made_phase = kx * line_x_m + ky * (geometry.origin_y_m + y_local_m) -
                                  made.angular_frequency_rad_s * t_s + made.phase_rad;
        const double field_phase = wave.wavenumber_x_rad_m * (line_x_m - geometry.origin_x_m) +
                                   wave.wavenumber_y_rad_m * y_local_m -
                                   wave.wave.angular_frequency_rad_s * t_s + wave.wave.phase_rad;
        EXPECT_NEAR(std::remainder(made_phase - field_phase, 2 * std::numbers::pi), 0.0, 1e-6)
            << "component " << i << " at y = " << y_local_m;
      }
  }
  EXPECT_GT(oblique, 0.0);  // the test does exercise oblique waves
  // The turn that keeps the tangential wavenumber with the model's |k| (Snell): measured 2.8 degrees
  // at most here (the loop's quantised frequencies and B = 1/15 both change |k| by up to 2 %).
  EXPECT_LT(largest_turn_rad, 5.0 * std::numbers::pi / 180.0);
}

// drive_wave_maker with the irregular maker: the same conversion, inside the maker's own band.
TEST_F(BakeDeepWater, IrregularMakerDrivenByTheFieldMakesTheFieldsWaves) {
  const auto folder = scratch_folder();
  const BakeCase c = read_bake_case(write_text(
      folder / "case.toml", flume_case(kIrregularMaker,
                                       "[deep_water]\ngrid_size = 64\ncascade_count = "
                                       "1\nshortest_wavelength_m = 0.5\ndrive_wave_maker = true\n")));
  ASSERT_TRUE(c.deep_water_maker.has_value());
  EXPECT_EQ(c.wave_conditions["driven_by_deep_water"], true);
  const double fraction = c.wave_conditions["deep_water_variance_fraction"].get<double>();
  EXPECT_GT(fraction, 0.5);
  EXPECT_LE(fraction, 1.0);
  const std::vector<WaveComponent>& made = c.wave_maker.sea_state.components;
  ASSERT_FALSE(made.empty());
  ASSERT_EQ(made.size(), c.deep_water_maker->carried.size());
  for (std::size_t i = 0; i < made.size(); ++i) {
    const WaveComponent& field = c.deep_water_maker->carried[i].wave;
    EXPECT_GT(std::cos(made[i].direction_rad), 0.2);  // eastward, away from the west source line
    EXPECT_GE(made[i].angular_frequency_rad_s, 2 * std::numbers::pi * 0.3 * 0.999);
    EXPECT_LE(made[i].angular_frequency_rad_s, 2 * std::numbers::pi * 1.2 * 1.001);
    EXPECT_EQ(made[i].amplitude_m, field.amplitude_m);
    EXPECT_EQ(made[i].angular_frequency_rad_s, field.angular_frequency_rad_s);
    // Turned (Snell) to keep the lattice's wavenumber along the line with the model's |k| at 0.5 m:
    // up to 5 degrees here, where the 32 s loop moves frequencies by up to 2.5 % and k d reaches 3.
    const double model_k =
        model_wavenumber(made[i].angular_frequency_rad_s, 0.5, c.solver.dispersion_coefficient);
    EXPECT_NEAR(model_k * std::sin(made[i].direction_rad), c.deep_water_maker->carried[i].wavenumber_y_rad_m,
                1e-9 * model_k);
  }
  EXPECT_DOUBLE_EQ(c.wave_maker.sea_state.loop_period_s, 32.0);
  BakeOptions options;
  options.output_folder = folder / "out";
  EXPECT_NO_THROW(run_bake(c, options));
}

// Every spectrum [deep_water] knows, on a harbour-scale basin (1.2 km x 400 m, 15 m deep, 8 m cells)
// with waves from the west: the field is the one asked for and the maker makes some of its waves.
TEST_F(BakeDeepWater, EverySpectrumKindIsRead) {
  const auto folder = scratch_folder();
  const std::string basin =
      "[bathymetry]\nkind = \"profile\"\nlength_m = 1200.0\nwidth_m = 400.0\nspacing_m = 8.0\nprofile = "
      "[[0.0, 15.0], [1200.0, 15.0]]\n"
      "[time]\nduration_s = 60.0\noutput_interval_s = 10.0\n"
      "[wave_maker]\nkind = \"deep_water\"\nfacing = \"west\"\nsource_line_m = 100.0\nloop_period_s = 600.0\n"
      "[deep_water]\ngrid_size = 32\ncascade_count = 1\n";
  const std::vector<std::pair<std::string, std::string>> spectra = {
      {"jonswap+cos2s",
       "spectrum = \"jonswap\"\nsignificant_height_m = 1.5\npeak_period_s = 10.0\nspreading_s = 20.0\n"},
      {"pierson-moskowitz+cos2s",
       "spectrum = \"pierson_moskowitz\"\nsignificant_height_m = 1.5\npeak_period_s = 10.0\n"},
      {"tma(jonswap)+cos2s",
       "spectrum = \"tma\"\nsignificant_height_m = 1.5\npeak_period_s = 10.0\ntma_depth_m = 15.0\n"},
      {"phillips",
       "spectrum = \"phillips\"\nwind_speed_m_s = 12.0\nsignificant_height_m = 1.5\nwind_direction_deg = "
       "10.0\n"},
      {"unified", "spectrum = \"unified\"\nwind_speed_10_m_s = 12.0\ninverse_wave_age = 0.9\n"},
      {"unified", "spectrum = \"unified\"\nwind_speed_10_m_s = 12.0\nfetch_m = 300000.0\n"},
      {"pm-ittc", "spectrum = \"pm_ittc\"\nwind_speed_10_m_s = 12.0\n"},
      {"unified", "spectrum = \"beaufort\"\nbeaufort_force = 6\n"},
      {"phillips", "spectrum = \"beaufort\"\nbeaufort_force = 6\nbeaufort_spectrum = \"phillips\"\n"},
  };
  for (const auto& [name, keys] : spectra) {
    const BakeCase c = read_bake_case(write_text(folder / "case.toml", basin + keys));
    ASSERT_TRUE(c.deep_water.has_value()) << keys;
    EXPECT_EQ(c.deep_water->spectrum->name(), name) << keys;
    EXPECT_NEAR(c.deep_water->still_water_depth_m, 15.0, 1e-9);
    ASSERT_TRUE(c.deep_water_maker.has_value());
    EXPECT_FALSE(c.wave_maker.sea_state.components.empty()) << keys;
    EXPECT_GT(c.deep_water_maker->variance_fraction(), 0.0) << keys;
  }
  // Beaufort 6 is the table's 3 m sea (seed 000 table 3.1), towards the default direction (east).
  const BakeCase beaufort = read_bake_case(write_text(folder / "case.toml", basin + spectra[7].second));
  EXPECT_NEAR(beaufort.deep_water->spectrum->significant_wave_height_m(), 3.0, 0.03);
  EXPECT_DOUBLE_EQ(beaufort.deep_water->spectrum->mean_direction_rad(), 0.0);
}

// Every bad [deep_water] or deep_water maker: one message naming the case file, the key and a fix.
TEST_F(BakeDeepWater, BadSectionsNameTheKeyAndTheFix) {
  scratch_folder();
  const std::string deep_maker = flume_case(kDeepWaterMaker, "");
  const auto with_field = [&](const std::string& from, const std::string& to) {
    std::string text = flume_case(kDeepWaterMaker, kDeepWaterField);
    const auto at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return text.replace(at, from.size(), to);
  };
  expect_case_error(deep_maker, {"key `deep_water` is missing", "takes its waves from it"});
  expect_case_error(with_field("spectrum = \"jonswap\"\n", ""), {"`deep_water.spectrum` is missing"});
  expect_case_error(with_field("\"jonswap\"", "\"bretschneider\""),
                    {"`deep_water.spectrum`", "is not known", "beaufort"});
  expect_case_error(with_field("spectrum = \"jonswap\"\n", "spectrum = \"beaufort\"\nbeaufort_force = 0\n"),
                    {"`deep_water.beaufort_force`", "out of range", "from 1 to 12"});
  expect_case_error(
      with_field("spectrum = \"jonswap\"\n",
                 "spectrum = \"unified\"\nwind_speed_10_m_s = 10.0\ninverse_wave_age = 1.0\nfetch_m = 1e5\n"),
      {"`deep_water.inverse_wave_age`", "both given"});
  expect_case_error(
      flume_case(kDeepWaterMaker,
                 "[deep_water]\nspectrum = \"unified\"\nwind_speed_10_m_s = 12.0\nfetch_m = 10.0\n"),
      {"`deep_water.spectrum` cannot be built", "Elfouhaily"});
  expect_case_error(with_field("cascade_count = 1\n", "tile_lengths_m = [10.0, 20.0]\n"),
                    {"`deep_water.tile_lengths_m`", "below the one before"});
  expect_case_error(with_field("seed = 5\n", "seed = 5\ntile_lengths_m = [10.0]\n"),
                    {"`deep_water.tile_lengths_m`", "cascade_count"});
  expect_case_error(with_field("seed = 5\n", "seed = 5\ndepth_m = 2.0\n"),
                    {"`deep_water.depth_m`", "source line's depth (0.500 m)"});
  expect_case_error(with_field("seed = 5\n", "seed = 5\ndrive_wave_maker = false\n"),
                    {"`deep_water.drive_wave_maker`"});
  expect_case_error(with_field("spreading_s = 10.0", "spreading_s = 5000.0"),
                    {"`deep_water.spreading_s`", "out of range"});
  expect_case_error(with_field("seed = 5\n", "seed = 5\nwind_speed_10_m_s = 10.0\n"),
                    {"`deep_water.wind_speed_10_m_s`", "not a known key"});
  expect_case_error(with_field("grid_size = 64", "grid_size = 100"),
                    {"`deep_water.grid_size`", "power of two"});
  expect_case_error(with_field("spreading_s = 10.0", "spreading_s = 10.0\nmean_direction_deg = 180.0"),
                    {"`deep_water`", "leaves the wave maker no component"});
  expect_case_error(with_field("loop_period_s = 32.0\n", "loop_period_s = 32.0\nseed = 5\n"),
                    {"`wave_maker.seed`", "move seed into [deep_water]"});
  expect_case_error(with_field("loop_period_s = 32.0\n", "loop_period_s = 32.0\nmax_frequency_hz = 5.0\n"),
                    {"`wave_maker.max_frequency_hz`", "above what the grid carries"});
  // [deep_water] with another maker.
  expect_case_error(small_flume_case() + "[deep_water]\n", {"`deep_water`", "irregular", "deep_water"});
  expect_case_error(flume_case(kIrregularMaker, "[deep_water]\nspectrum = \"jonswap\"\n"),
                    {"`deep_water.spectrum` is the irregular wave maker's"});
  std::string long_crested = kIrregularMaker;
  const std::string spread = "spreading_s = 10.0\ndirection_count = 8\n";
  long_crested.replace(long_crested.find(spread), spread.size(), "");
  expect_case_error(flume_case(long_crested, "[deep_water]\n"),
                    {"`deep_water`", "long-crested", "wave_maker.spreading_s"});
}

}  // namespace
}  // namespace nearshore::bake
