#include "nearshore/runtime/deep_water_source.hpp"

#include <cmath>
#include <limits>
#include <numbers>

#include <fmt/format.h>

#include "nearshore/core/error.hpp"
#include "nearshore/ocean/sea_state_beaufort.hpp"
#include "nearshore/sequence/checksum.hpp"
#include "nearshore/sequence/deep_water_section.hpp"

namespace nearshore::runtime {

std::optional<ocean::RecordedDeepWater> read_recorded_deep_water(const sequence::SequenceReader& reader,
                                                                 sequence::Verify verify) {
  const std::optional<sequence::DeepWaterSection>& section = reader.manifest().deep_water;
  if (!section || section->cascades.empty()) return std::nullopt;
  for (const sequence::DeepWaterCascadeRecord& cascade : section->cascades)
    if (!cascade.coefficients) return std::nullopt;
  ocean::RecordedDeepWater recorded;
  recorded.still_water_depth_m = section->still_water_depth_m;
  recorded.loop_period_s = section->loop_period_s;
  recorded.choppiness = section->choppiness;
  recorded.seed = section->seed;
  recorded.unresolved_slope_variance = section->unresolved_slope_variance;
  const std::string fix = fmt::format("bake {} again (its deep-water coefficient files do not match its manifest)",
                                      reader.folder().string());
  for (const sequence::DeepWaterCascadeRecord& cascade : section->cascades) {
    const std::filesystem::path file = reader.folder() / cascade.coefficients->file;
    if (verify == sequence::Verify::kYes) {
      const std::string bytes = sequence::read_file_bytes(file);
      if (bytes.size() != cascade.coefficients->bytes ||
          sequence::checksum_text(std::as_bytes(std::span(bytes.data(), bytes.size()))) != cascade.coefficients->checksum)
        throw Error(file.string(), "does not match the size and checksum manifest.json lists for it", fix);
    }
    const sequence::DeepWaterCoefficients c = sequence::read_deep_water_coefficients(file);
    if (c.grid_size != cascade.grid_size || std::abs(c.tile_length_m - cascade.tile_length_m) > 1e-9 * cascade.tile_length_m ||
        std::abs(c.loop_period_s - section->loop_period_s) > 1e-9 * std::max(1.0, section->loop_period_s))
      throw Error(file.string(),
                  fmt::format("holds N = {}, L = {} m, T_loop = {} s but the manifest says N = {}, L = {} m, T_loop = {} s",
                              c.grid_size, c.tile_length_m, c.loop_period_s, cascade.grid_size, cascade.tile_length_m,
                              section->loop_period_s),
                  fix);
    ocean::RecordedCascade out;
    out.grid_size = c.grid_size;
    out.tile_length_m = c.tile_length_m;
    out.min_wavenumber_rad_m = cascade.min_wavenumber_rad_m;
    out.max_wavenumber_rad_m = cascade.max_wavenumber_rad_m;
    out.amplitude_m = c.amplitude_m;
    out.phase_rad.assign(c.phase_rad.begin(), c.phase_rad.end());
    out.harmonic.assign(c.harmonic.begin(), c.harmonic.end());
    out.angular_frequency_rad_s.resize(c.angular_frequency_rad_s.size());
    const double fundamental_rad_s = c.loop_period_s > 0.0 ? 2.0 * std::numbers::pi / c.loop_period_s : 0.0;
    for (std::size_t i = 0; i < out.angular_frequency_rad_s.size(); ++i)
      // Looping: the harmonic is exact and the float32 frequency is not (the bake used the harmonic).
      out.angular_frequency_rad_s[i] = fundamental_rad_s > 0.0 && c.harmonic[i] >= 0
                                           ? static_cast<double>(c.harmonic[i]) * fundamental_rad_s
                                           : static_cast<double>(c.angular_frequency_rad_s[i]);
    recorded.cascades.push_back(std::move(out));
  }
  return recorded;
}

std::optional<SpectrumSplitRecord> read_spectrum_split(const sequence::SequenceManifest& manifest,
                                                       const std::string& manifest_name) {
  const nlohmann::json& conditions = manifest.wave_conditions;
  if (!conditions.is_object() || !conditions.contains("spectrum_split")) return std::nullopt;
  const nlohmann::json& split = conditions["spectrum_split"];
  const std::string fix = "bake the sequence again (the bake writes this record; docs/commands/bake.md \"The spectrum is split\")";
  if (!split.is_object())
    throw Error(manifest_name, "wave_conditions.spectrum_split is not an object", fix);
  const auto number = [&](const char* key, bool required, double fallback) {
    if (!split.contains(key)) {
      if (required) throw Error(manifest_name, fmt::format("wave_conditions.spectrum_split has no {}", key), fix);
      return fallback;
    }
    if (!split[key].is_number() || !std::isfinite(split[key].get<double>()) || split[key].get<double>() < 0.0)
      throw Error(manifest_name, fmt::format("wave_conditions.spectrum_split.{} is not a non-negative number", key), fix);
    return split[key].get<double>();
  };
  SpectrumSplitRecord record;
  record.bake_min_frequency_hz = number("bake_min_frequency_hz", true, 0.0);
  record.bake_max_frequency_hz = number("bake_max_frequency_hz", true, 0.0);
  record.split_frequency_hz = number("split_frequency_hz", false, record.bake_max_frequency_hz);
  record.bake_significant_wave_height_m = number("bake_significant_wave_height_m", true, 0.0);
  record.deep_water_significant_wave_height_m = number("deep_water_significant_wave_height_m", true, 0.0);
  record.total_significant_wave_height_m = number("total_significant_wave_height_m", true, 0.0);
  record.deep_water_layer_present =
      split.contains("deep_water_layer_present") && split["deep_water_layer_present"].is_boolean() &&
      split["deep_water_layer_present"].get<bool>();
  if (!(record.split_frequency_hz > 0.0))
    throw Error(manifest_name, "wave_conditions.spectrum_split.split_frequency_hz is 0", fix);
  return record;
}

double DeepWaterInsideLayer::significant_wave_height_m() const { return 4.0 * std::sqrt(variance_m2); }

DeepWaterInsideLayer split_deep_water(const ocean::RecordedDeepWater& field, double split_angular_frequency_rad_s) {
  if (!(split_angular_frequency_rad_s > 0.0) || !std::isfinite(split_angular_frequency_rad_s))
    throw Error("split_deep_water", fmt::format("split_angular_frequency_rad_s = {}", split_angular_frequency_rad_s),
                "give the split frequency of the manifest's wave_conditions.spectrum_split (positive, rad/s)");
  DeepWaterInsideLayer layer;
  layer.split_angular_frequency_rad_s = split_angular_frequency_rad_s;
  layer.lowest_angular_frequency_rad_s = std::numeric_limits<double>::infinity();
  // The bake's own guard (case_sea_state.cpp: a band ends at w (1 + 1e-9)), so a component the
  // maker made at the band's top is never drawn again.
  const double above_rad_s = split_angular_frequency_rad_s * (1.0 + 1e-9);
  layer.straddling.still_water_depth_m = field.still_water_depth_m;
  layer.straddling.loop_period_s = field.loop_period_s;
  layer.straddling.choppiness = field.choppiness;
  layer.straddling.seed = field.seed;
  layer.straddling.unresolved_slope_variance = 0.0;  // the lighting takes it from the whole field
  for (std::size_t c = 0; c < field.cascades.size(); ++c) {
    const ocean::RecordedCascade& cascade = field.cascades[c];
    int above = 0, below = 0;
    for (std::size_t i = 0; i < cascade.amplitude_m.size(); ++i) {
      if (cascade.amplitude_m[i] == 0.0f) continue;
      const double w = cascade.angular_frequency_rad_s[i];
      if (w > above_rad_s) {
        ++above;
        const double a = cascade.amplitude_m[i];
        layer.variance_m2 += 0.5 * a * a;
        layer.lowest_angular_frequency_rad_s = std::min(layer.lowest_angular_frequency_rad_s, w);
      } else {
        ++below;
      }
    }
    layer.component_count += above;
    if (above == 0) continue;  // wholly the bake's (or below it): not drawn inside
    if (below == 0) {
      layer.whole_cascade_mask |= std::uint32_t{1} << c;
      continue;
    }
    // Straddling: the same lattice with the bake's components (and any below them) zeroed.
    ocean::RecordedCascade kept = cascade;
    for (std::size_t i = 0; i < kept.amplitude_m.size(); ++i)
      if (!(kept.angular_frequency_rad_s[i] > above_rad_s)) kept.amplitude_m[i] = 0.0f;
    layer.straddling.cascades.push_back(std::move(kept));
    layer.straddling_cascades.push_back(static_cast<int>(c));
  }
  if (layer.component_count == 0) layer.lowest_angular_frequency_rad_s = 0.0;
  return layer;
}

std::unique_ptr<ocean::DeepWaterField> build_beaufort_field(const BeaufortSea& sea) {
  const ocean::BeaufortPreset preset = ocean::beaufort_preset(sea.force, sea.wind_direction_rad);
  if (!preset.spectrum) return nullptr;  // force 0: calm
  ocean::DeepWaterSpecification spec;
  spec.spectrum = preset.spectrum;
  spec.grid_size = sea.grid_size;
  spec.tile_lengths_m =
      ocean::cascade_tile_lengths_for_m(*preset.spectrum, sea.grid_size, sea.cascade_count, sea.shortest_wavelength_m);
  spec.still_water_depth_m = 0.0;
  spec.loop_period_s = 0.0;
  spec.choppiness = sea.choppiness;
  spec.seed = sea.seed;
  return std::make_unique<ocean::DeepWaterField>(spec);
}

BakeTimes bake_times(const PlanStep& now, const PlanStep& next, double fraction, double frame_interval_s,
                     double first_frame_time_s) {
  BakeTimes result;
  const auto bake_time = [&](int frame) { return first_frame_time_s + frame * frame_interval_s; };
  const auto add = [&](double time_s, double weight) {
    if (weight == 0.0) return;
    // Consecutive steps of one timeline name the same bake time twice (up to round-off).
    for (int i = 0; i < result.count; ++i)
      if (std::abs(result.times[static_cast<std::size_t>(i)].time_s - time_s) <= 1e-9 * std::max(1.0, std::abs(time_s))) {
        result.times[static_cast<std::size_t>(i)].weight += weight;
        return;
      }
    result.times[static_cast<std::size_t>(result.count++)] = {time_s, weight};
  };
  const double ahead_s = fraction * frame_interval_s, behind_s = (fraction - 1.0) * frame_interval_s;
  const double w_now = now.shown.target_weight, w_next = next.shown.target_weight;
  add(bake_time(now.shown.source_frame) + ahead_s, (1.0 - fraction) * (1.0 - w_now));
  add(bake_time(now.shown.target_frame) + ahead_s, (1.0 - fraction) * w_now);
  add(bake_time(next.shown.source_frame) + behind_s, fraction * (1.0 - w_next));
  add(bake_time(next.shown.target_frame) + behind_s, fraction * w_next);
  return result;
}

}  // namespace nearshore::runtime
