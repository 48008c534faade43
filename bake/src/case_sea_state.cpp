// The sea of a case file: spectra by name through ocean's registry, and [deep_water] (the FFT field
// beyond the harbour, docs/commands/bake.md).
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <fmt/core.h>

#include "nearshore/core/error.hpp"
#include "case_reader.hpp"

namespace nearshore::bake::detail {

using namespace nearshore::ocean;       // spectra, sea states, the deep-water field
using namespace nearshore::boussinesq;  // the solver and its parameters

namespace {

// Physical bounds of the spectra's parameters, beyond the registry's own ranges (which leave most
// of them open above): what the Earth's seas and winds have. 1e308 s as a peak period overflowed
// the sea-state builder (found by the case-file fuzzer).
struct PlausibleRange {
  const char* key;
  double lowest, highest;
  const char* why;
};
constexpr PlausibleRange kPlausibleSpectrumParameters[] = {
    {"significant_height_m", 0.0, 30.0, "the highest significant wave height measured is 19 m (North Atlantic, 2013)"},
    {"peak_period_s", 0.1, 86400.0, "below 0.1 s surface tension governs the waves; above a day it is no wave a harbour bake makes"},
    {"tma_depth_m", 0.0, 11000.0, "no water is deeper than the Challenger Deep, 10 935 m"},
    {"wind_speed_m_s", 0.0, 120.0, "the strongest gust measured is 113 m/s (Barrow Island, 1996)"},
    {"wind_speed_10_m_s", 0.0, 120.0, "the strongest gust measured is 113 m/s (Barrow Island, 1996)"},
    {"fetch_m", 0.0, 2.0e7, "no fetch is longer than half the Earth's circumference"},
};

// The case file's table as the registry's parameter reader: its checks, messages and key tracking.
class TableSpectrumParameters final : public SpectrumParameters {
 public:
  explicit TableSpectrumParameters(TableReader& table) : table_(table) {}
  bool has(const std::string& key) const override { return table_.has(key); }
  double number(const std::string& key, std::optional<double> fallback, double minimum, double maximum,
                bool exclusive_minimum, const std::string& meaning) override {
    const double value = table_.number(key, fallback, minimum, maximum, exclusive_minimum, meaning);
    for (const PlausibleRange& range : kPlausibleSpectrumParameters)
      if (key == range.key && (value < range.lowest || value > range.highest))
        table_.fail(table_.full(key), fmt::format("= {} is outside {} .. {} ({})", value, range.lowest, range.highest, range.why),
                    "give " + meaning);
    return value;
  }
  int integer(const std::string& key, std::optional<int> fallback, int minimum, int maximum,
              const std::string& meaning) override {
    return table_.integer(key, fallback, minimum, maximum, meaning);
  }
  std::size_t choice(const std::string& key, std::optional<std::string> fallback,
                     const std::vector<std::string>& choices) override {
    return table_.choice(key, std::move(fallback), choices);
  }
  [[noreturn]] void fail(const std::string& key, const std::string& problem, const std::string& fix) override {
    table_.fail(table_.full(key), problem, fix);
  }

 private:
  TableReader& table_;
};

}  // namespace

std::shared_ptr<const FrequencySpectrum> read_frequency_spectrum(TableReader& table, const std::string& key,
                                                                 std::optional<std::string> fallback) {
  const std::vector<std::string> names = spectrum_names(/*with_frequency_spectrum_only=*/true);
  const SpectrumEntry& entry = spectrum_entry(names[table.choice(key, std::move(fallback), names)]);
  TableSpectrumParameters parameters(table);
  return entry.frequency(parameters);
}

std::shared_ptr<const WavenumberSpectrum> read_wavenumber_spectrum(TableReader& table, const std::string& key,
                                                                   const SpectrumDefaults& defaults) {
  const std::vector<std::string> names = spectrum_names(/*with_frequency_spectrum_only=*/false);
  const SpectrumEntry& entry = spectrum_entry(names[table.choice(key, std::nullopt, names)]);
  TableSpectrumParameters parameters(table);
  return entry.wavenumber(parameters, defaults);
}

// [deep_water] (docs/commands/bake.md): the FFT field beyond the harbour. With an irregular wave
// maker it is made from the maker's spectrum and spreading (DirectionalWavenumberSpectrum at the
// source line's depth), loop period and seed, so both sides describe one sea; with
// wave_maker.kind = "deep_water" it has its own spectrum and seed and gives the maker its waves.
DeepWaterSpecification read_deep_water(TableReader& deep, const WaveMaker& maker, const MakerRequest& request,
                                       const HarbourGrid& grid, DeepWaterDrive& drive, BakeCase& bake_case) {
  if (!request.spectrum && !request.from_deep_water)
    deep.fail("deep_water",
              "needs a wave maker that makes the same sea: an irregular one (whose spectrum, spreading, loop "
              "period and "
              "seed the field shares) or one made from the field",
              "set wave_maker.kind = \"irregular\" or \"deep_water\", or remove [deep_water]");
  if (request.long_crested)
    deep.fail("deep_water",
              "cannot share a long-crested irregular wave maker's sea (wave_maker.spreading_s = 0): the FFT "
              "lattice needs "
              "a directional spread",
              "set wave_maker.spreading_s (e.g. 75 for a swell, 20 for a wind sea)");
  if (request.spectrum)
    for (const char* key : {"spectrum", "seed"})
      if (deep.has(key))
        deep.fail(deep.full(key), "is the irregular wave maker's, which the field shares",
                  "set it in [wave_maker], or use wave_maker.kind = \"deep_water\" for a field with its own "
                  "spectrum");
  DeepWaterSpecification specification;
  specification.grid_size = deep.integer("grid_size", 256, 8, 4096, "samples per tile side, a power of two");
  if ((specification.grid_size & (specification.grid_size - 1)) != 0)
    deep.fail(deep.full("grid_size"), fmt::format("= {} is not a power of two", specification.grid_size), "use 64, 128, 256 or 512");
  const bool explicit_tiles = deep.has("tile_lengths_m");
  if (explicit_tiles && (deep.has("cascade_count") || deep.has("shortest_wavelength_m")))
    deep.fail(deep.full("tile_lengths_m"), "is given with cascade_count or shortest_wavelength_m",
              "give either the tile lengths or the cascade count and shortest wavelength (which lay the "
              "tiles out)");
  if (explicit_tiles) {
    specification.tile_lengths_m =
        deep.numbers("tile_lengths_m", 0, "[L_0, L_1, ...] in metres, strictly decreasing");
    for (std::size_t i = 0; i < specification.tile_lengths_m.size(); ++i)
      if (!(specification.tile_lengths_m[i] > 0.0) ||
          (i > 0 && !(specification.tile_lengths_m[i] < specification.tile_lengths_m[i - 1])))
        deep.fail(deep.full("tile_lengths_m"),
                  fmt::format("has {} m at position {}, not positive and below the one before",
                              specification.tile_lengths_m[i], i),
                  "list the tile lengths in metres from the largest down, e.g. [1000.0, 270.0, 73.0]");
    if (specification.tile_lengths_m.size() > 8)
      deep.fail(deep.full("tile_lengths_m"), fmt::format("has {} tiles", specification.tile_lengths_m.size()),
                "use at most 8 cascades");
  }
  const int cascade_count = explicit_tiles ? static_cast<int>(specification.tile_lengths_m.size())
                                           : deep.integer("cascade_count", 3, 1, 8,
                                                          "number of cascades (tiles of decreasing length)");
  const double shortest_wavelength_m =
      explicit_tiles ? 0.0
                     : deep.positive("shortest_wavelength_m", 0.5,
                                     "shortest wavelength the last cascade resolves, metres");
  specification.choppiness = deep.number("choppiness", 1.0, 0.0, 2.0, false, "lambda of the choppy displacement (0 = none)");
  drive.drives_wave_maker = request.from_deep_water || deep.boolean("drive_wave_maker", false);
  if (request.from_deep_water && !deep.boolean("drive_wave_maker", true))
    deep.fail(deep.full("drive_wave_maker"),
              "= false, but wave_maker.kind = \"deep_water\" takes its waves from the field",
              "remove drive_wave_maker, or give the wave maker its own kind");
  const double default_depth_m = source_line_depth_m(maker, grid);
  if (drive.drives_wave_maker && deep.has("depth_m"))
    deep.fail(
        deep.full("depth_m"),
        fmt::format(
            "is given, but a field that drives the wave maker must use the source line's depth ({:.3f} m)",
            default_depth_m),
        "remove depth_m: the field and the baked waves then share one dispersion relation at the offshore "
        "edge");
  specification.still_water_depth_m =
      deep.non_negative("depth_m", default_depth_m, "still-water depth of the dispersion relation, metres (0 = deep water)");
  specification.loop_period_s = maker.sea_state.loop_period_s;
  specification.seed =
      request.from_deep_water ? deep.unsigned_integer("seed", 1, "phase seed") : maker.sea_state.seed;
  bake_case.deep_water_tile_set_frame_interval_s =
      deep.non_negative("tile_set_frame_interval_s", 0.0, "frame interval of the baked tile set in seconds (0 = none)");
  bake_case.deep_water_tile_set_cascade = deep.integer("tile_set_cascade", 0, 0, cascade_count - 1, "the cascade the tile set bakes");
  if (bake_case.deep_water_tile_set_frame_interval_s > 0) {
    const double loop_s = specification.loop_period_s;
    const double frames = loop_s / bake_case.deep_water_tile_set_frame_interval_s;
    if (loop_s <= 0 || std::abs(frames - std::round(frames)) > 1e-9 * frames || frames < 2)
      deep.fail(deep.full("tile_set_frame_interval_s"),
                fmt::format("= {} s must divide wave_maker.loop_period_s = {} s into 2 or more frames (a tile set is one loop)",
                            bake_case.deep_water_tile_set_frame_interval_s, loop_s),
                "set wave_maker.loop_period_s and a frame interval that divides it, or remove tile_set_frame_interval_s");
  }
  specification.spectrum = request.from_deep_water
                               ? read_wavenumber_spectrum(deep, "spectrum",
                                                          {direction_away_from(maker.facing), specification.still_water_depth_m})
                               : std::make_shared<DirectionalWavenumberSpectrum>(
                                     request.spectrum, request.spreading, specification.still_water_depth_m);
  // [[deep_water.local_sea]]: seas the harbour's own wind raises over its fetch (issue 14: Tacoma's
  // Hs 0.6 m, Tp 3.5 s wind sea under the swell). They do not come in through the source line, so the
  // bake carries none of them and nothing is counted twice: they are the FFT layer's alone, added to
  // its spectrum (independent seas: variances add). Inside the harbour the runtime draws the layer
  // above the split frequency only (docs/runtime.md "The split"); a local sea's variance below it is
  // not drawn there, which the bake reports (describe_carried_band).
  std::vector<TableReader> local_seas = deep.tables("local_sea");
  if (!local_seas.empty()) {
    if (drive.drives_wave_maker)
      deep.fail(deep.full("local_sea"),
                "is given, but the field drives the wave maker, which would then make the local sea at the source "
                "line as well",
                "use an irregular wave maker for the swell (wave_maker.kind = \"irregular\") without "
                "deep_water.drive_wave_maker, and keep the local sea here");
    std::vector<std::shared_ptr<const WavenumberSpectrum>> parts{specification.spectrum};
    for (TableReader& sea : local_seas) {
      parts.push_back(read_wavenumber_spectrum(sea, "spectrum", {direction_away_from(maker.facing), specification.still_water_depth_m}));
      sea.finish();
    }
    specification.spectrum = std::make_shared<SpectrumSum>(std::move(parts));
  }
  try {
    if (!explicit_tiles)
      specification.tile_lengths_m = cascade_tile_lengths_for_m(
          *specification.spectrum, specification.grid_size, cascade_count, shortest_wavelength_m);
  } catch (const Error& error) {
    deep.fail("deep_water", "cannot be laid out: " + error.problem(), error.fix());
  }
  // The band of the field the maker makes: kind "deep_water" says it; an irregular maker driven by
  // the field keeps the band its own discretisation chose (what the grid carries, checked above).
  drive.band = request.band;
  if (!request.from_deep_water && !maker.sea_state.components.empty()) {
    const auto [lowest, highest] =
        std::minmax_element(maker.sea_state.components.begin(), maker.sea_state.components.end(),
                            [](const WaveComponent& a, const WaveComponent& b) {
                              return a.angular_frequency_rad_s < b.angular_frequency_rad_s;
                            });
    drive.band.min_frequency_rad_s = lowest->angular_frequency_rad_s * (1 - 1e-9);
    drive.band.max_frequency_rad_s = highest->angular_frequency_rad_s * (1 + 1e-9);
  }
  return specification;
}


}  // namespace nearshore::bake::detail
