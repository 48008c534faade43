#include "nearshore/sequence/deep_water_section.hpp"

#include <cstring>

#include <fmt/core.h>

#include "nearshore/core/atomic_file.hpp"
#include "nearshore/core/error.hpp"
#include "nearshore/core/hash.hpp"
#include "nearshore/sequence/checksum.hpp"
#include "json_fields.hpp"

namespace nearshore::sequence {
namespace {

using value_t = nlohmann::json::value_t;

// Text the section carries for people reading the manifest; the fields above it are the contract.
constexpr const char* kFrameText =
    "the field's x = 0, y = 0 is the harbour grid's south-west corner (geometry origin_x_m, origin_y_m); "
    "x east, y north, m";
constexpr const char* kTimeText =
    "the field's t is the bake's simulated time: frame k is at first_frame_time_s + k frame_interval_s";
constexpr const char* kWeightText =
    "w(s) = 0 for s <= start_m, sin^2(pi/2 (s - start_m) / width_m) inside, 1 beyond; shown = (1 - w) fft + w baked";

constexpr char kCoefficientMagic[8] = {'N', 'S', 'D', 'W', 'C', 'O', 'E', 'F'};
constexpr std::uint32_t kCoefficientVersion = 1;
constexpr std::size_t kCoefficientHeaderBytes = 8 + 4 + 4 + 8 + 8, kCoefficientRecordBytes = 16;

const nlohmann::json& require_object(const nlohmann::json& object, const char* key, const std::string& source) {
  return require(object, key, value_t::object, source);
}
bool require_bool(const nlohmann::json& object, const char* key, const std::string& source) {
  return require(object, key, value_t::boolean, source).get<bool>();
}
std::uint64_t require_count(const nlohmann::json& object, const char* key, const std::string& source) {
  return require(object, key, value_t::number_unsigned, source).get<std::uint64_t>();
}
int require_small_count(const nlohmann::json& object, const char* key, const std::string& source, std::uint64_t limit) {
  const std::uint64_t value = require_count(object, key, source);
  if (value > limit)
    throw Error(source, fmt::format("deep_water \"{}\" is {}, above {}", key, value, limit),
                "the manifest is corrupt; rewrite the sequence");
  return static_cast<int>(value);
}

DeepWaterCascadeRecord parse_cascade(const nlohmann::json& json, const std::string& source) {
  if (!json.is_object()) throw Error(source, "a deep_water cascade is not an object", "rewrite the sequence");
  DeepWaterCascadeRecord cascade;
  cascade.tile_length_m = require_number(json, "tile_length_m", source);
  cascade.grid_size = require_small_count(json, "grid_size", source, 4096);
  cascade.min_wavenumber_rad_m = require_number(json, "min_wavenumber_rad_m", source);
  cascade.max_wavenumber_rad_m = require_number(json, "max_wavenumber_rad_m", source);
  cascade.variance_m2 = require_number(json, "variance_m2", source);
  cascade.slope_variance = require_number(json, "slope_variance", source);
  if (json.contains("coefficients_file")) {
    FileEntry file;
    file.file = require_string(json, "coefficients_file", source);
    file.bytes = require_count(json, "coefficients_bytes", source);
    file.checksum = require_string(json, "coefficients_checksum", source);
    if (file.file.empty() || file.file.find('/') != std::string::npos || file.file.find('\\') != std::string::npos ||
        file.file == "." || file.file == "..")
      throw Error(source, fmt::format("deep_water coefficients_file \"{}\" is not a file name in the folder", file.file),
                  "the manifest is corrupt; rewrite the sequence");
    cascade.coefficients = file;
  }
  return cascade;
}

}  // namespace

nlohmann::json deep_water_section_to_json(const DeepWaterSection& section) {
  nlohmann::json cascades = nlohmann::json::array();
  for (const DeepWaterCascadeRecord& cascade : section.cascades) {
    nlohmann::json entry = {{"tile_length_m", cascade.tile_length_m},
                            {"grid_size", cascade.grid_size},
                            {"min_wavenumber_rad_m", cascade.min_wavenumber_rad_m},
                            {"max_wavenumber_rad_m", cascade.max_wavenumber_rad_m},
                            {"variance_m2", cascade.variance_m2},
                            {"slope_variance", cascade.slope_variance}};
    if (cascade.coefficients) {
      entry["coefficients_file"] = cascade.coefficients->file;
      entry["coefficients_bytes"] = cascade.coefficients->bytes;
      entry["coefficients_checksum"] = cascade.coefficients->checksum;
    }
    cascades.push_back(std::move(entry));
  }
  nlohmann::json json = {{"format", kDeepWaterSectionFormat},
                         {"spectrum", section.spectrum},
                         {"mean_direction_rad", section.mean_direction_rad},
                         {"still_water_depth_m", section.still_water_depth_m},
                         {"loop_period_s", section.loop_period_s},
                         {"choppiness", section.choppiness},
                         {"seed", section.seed},
                         {"significant_wave_height_m", section.significant_wave_height_m},
                         {"spectrum_significant_wave_height_m", section.spectrum_significant_wave_height_m},
                         {"unresolved_slope_variance", section.unresolved_slope_variance},
                         {"foam", {{"breaking_jacobian", section.foam_breaking_jacobian}, {"choppiness", section.choppiness}}},
                         {"cascades", cascades}};
  if (const auto& coupling = section.coupling) {
    nlohmann::json entry = {{"origin_x_m", coupling->origin_x_m},
                            {"origin_y_m", coupling->origin_y_m},
                            {"frame", kFrameText},
                            {"time", kTimeText},
                            {"drives_wave_maker", coupling->drives_wave_maker}};
    if (const auto& maker = coupling->wave_maker)
      entry["wave_maker"] = {{"components", maker->components},
                             {"variance_fraction", maker->variance_fraction},
                             {"field_variance_m2", maker->field_variance_m2},
                             {"carried_variance_m2", maker->carried_variance_m2},
                             {"carried_significant_wave_height_m", maker->carried_significant_wave_height_m},
                             {"source_depth_m", maker->source_depth_m},
                             {"min_frequency_hz", maker->min_frequency_hz},
                             {"max_frequency_hz", maker->max_frequency_hz}};
    if (const auto& blending = coupling->blending)
      entry["blending"] = {{"side", blending->side},
                           {"axis", blending->axis},
                           {"source_line_m", blending->source_line_m},
                           {"start_m", blending->start_m},
                           {"width_m", blending->width_m},
                           {"weight", kWeightText},
                           {"predicted_relative_rms_start", blending->predicted_relative_rms_start},
                           {"predicted_relative_rms_end", blending->predicted_relative_rms_end},
                           {"seamless", blending->seamless},
                           {"seamless_relative_rms", blending->seamless_relative_rms}};
    json["coupling"] = std::move(entry);
  }
  if (const auto& tiles = section.tile_set)
    json["tile_set"] = {{"folder", tiles->folder},
                        {"cascade", tiles->cascade},
                        {"frames", tiles->frames},
                        {"frame_interval_s", tiles->frame_interval_s},
                        {"bytes", tiles->bytes}};
  if (section.tile_set_cascade) json["tile_set_cascade"] = *section.tile_set_cascade;
  return json;
}

DeepWaterSection parse_deep_water_section(const nlohmann::json& json, const std::string& source) {
  if (!json.is_object()) throw Error(source, "\"deep_water\" is not an object", "the manifest is corrupt; rewrite the sequence");
  const std::string format = require_string(json, "format", source);
  if (format != kDeepWaterSectionFormat)
    throw Error(source, fmt::format("deep_water has format \"{}\"; this reader knows \"{}\"", format, kDeepWaterSectionFormat),
                "read it with the nearshore version that wrote it, or bake again");
  DeepWaterSection section;
  section.spectrum = require_object(json, "spectrum", source);
  section.mean_direction_rad = require_number(json, "mean_direction_rad", source);
  section.still_water_depth_m = require_number(json, "still_water_depth_m", source);
  section.loop_period_s = require_number(json, "loop_period_s", source);
  section.choppiness = require_number(json, "choppiness", source);
  section.seed = require_count(json, "seed", source);
  section.significant_wave_height_m = require_number(json, "significant_wave_height_m", source);
  section.spectrum_significant_wave_height_m = require_number(json, "spectrum_significant_wave_height_m", source);
  section.unresolved_slope_variance = require_number(json, "unresolved_slope_variance", source);
  section.foam_breaking_jacobian = require_number(require_object(json, "foam", source), "breaking_jacobian", source);
  const nlohmann::json& cascades = require(json, "cascades", value_t::array, source);
  if (cascades.empty() || cascades.size() > 16)
    throw Error(source, fmt::format("deep_water lists {} cascades", cascades.size()), "rewrite the sequence");
  for (const nlohmann::json& cascade : cascades) section.cascades.push_back(parse_cascade(cascade, source));
  if (json.contains("coupling")) {
    const nlohmann::json& entry = require_object(json, "coupling", source);
    DeepWaterCouplingRecord coupling;
    coupling.origin_x_m = require_number(entry, "origin_x_m", source);
    coupling.origin_y_m = require_number(entry, "origin_y_m", source);
    coupling.drives_wave_maker = require_bool(entry, "drives_wave_maker", source);
    if (entry.contains("wave_maker")) {
      const nlohmann::json& maker_json = require_object(entry, "wave_maker", source);
      DeepWaterMakerRecord maker;
      maker.components = require_count(maker_json, "components", source);
      maker.variance_fraction = require_number(maker_json, "variance_fraction", source);
      maker.field_variance_m2 = require_number(maker_json, "field_variance_m2", source);
      maker.carried_variance_m2 = require_number(maker_json, "carried_variance_m2", source);
      maker.carried_significant_wave_height_m = require_number(maker_json, "carried_significant_wave_height_m", source);
      maker.source_depth_m = require_number(maker_json, "source_depth_m", source);
      maker.min_frequency_hz = require_number(maker_json, "min_frequency_hz", source);
      maker.max_frequency_hz = require_number(maker_json, "max_frequency_hz", source);
      coupling.wave_maker = maker;
    }
    if (entry.contains("blending")) {
      const nlohmann::json& blending_json = require_object(entry, "blending", source);
      DeepWaterBlendingRecord blending;
      blending.side = require_string(blending_json, "side", source);
      blending.axis = require_string(blending_json, "axis", source);
      if ((blending.axis != "x" && blending.axis != "y") ||
          (blending.side != "west" && blending.side != "east" && blending.side != "south" && blending.side != "north"))
        throw Error(source, fmt::format("deep_water blending side \"{}\" / axis \"{}\" is not a grid side", blending.side, blending.axis),
                    "the manifest is corrupt; rewrite the sequence");
      blending.source_line_m = require_number(blending_json, "source_line_m", source);
      blending.start_m = require_number(blending_json, "start_m", source);
      blending.width_m = require_number(blending_json, "width_m", source);
      blending.predicted_relative_rms_start = require_number(blending_json, "predicted_relative_rms_start", source);
      blending.predicted_relative_rms_end = require_number(blending_json, "predicted_relative_rms_end", source);
      blending.seamless = require_bool(blending_json, "seamless", source);
      blending.seamless_relative_rms = require_number(blending_json, "seamless_relative_rms", source);
      coupling.blending = blending;
    }
    section.coupling = coupling;
  }
  if (json.contains("tile_set")) {
    const nlohmann::json& entry = require_object(json, "tile_set", source);
    DeepWaterTileSetRecord tiles;
    tiles.folder = require_string(entry, "folder", source);
    tiles.cascade = require_small_count(entry, "cascade", source, 16);
    tiles.frames = require_small_count(entry, "frames", source, 10'000'000);
    tiles.frame_interval_s = require_number(entry, "frame_interval_s", source);
    tiles.bytes = require_count(entry, "bytes", source);
    section.tile_set = tiles;
  }
  if (json.contains("tile_set_cascade")) section.tile_set_cascade = require_small_count(json, "tile_set_cascade", source, 16);
  return section;
}

std::string deep_water_coefficients_file_name(int index) { return fmt::format("deep_water_cascade_{}.bin", index); }

FileEntry write_deep_water_coefficients(const std::filesystem::path& folder, int index,
                                        const DeepWaterCoefficients& coefficients) {
  const std::size_t records = static_cast<std::size_t>(coefficients.grid_size) * coefficients.grid_size;
  if (coefficients.amplitude_m.size() != records || coefficients.phase_rad.size() != records ||
      coefficients.angular_frequency_rad_s.size() != records || coefficients.harmonic.size() != records)
    throw Error(folder.string(), fmt::format("deep-water cascade {} has arrays of the wrong size for N = {}", index,
                                             coefficients.grid_size),
                "give N x N amplitudes, phases, frequencies and harmonics");
  std::vector<std::byte> bytes;
  bytes.reserve(kCoefficientHeaderBytes + records * kCoefficientRecordBytes);
  const auto append = [&bytes](const auto& value) {
    const auto* raw = reinterpret_cast<const std::byte*>(&value);
    bytes.insert(bytes.end(), raw, raw + sizeof(value));
  };
  for (char c : kCoefficientMagic) append(c);
  append(kCoefficientVersion);
  append(static_cast<std::uint32_t>(coefficients.grid_size));
  append(coefficients.tile_length_m);
  append(coefficients.loop_period_s);
  for (std::size_t k = 0; k < records; ++k) {
    append(coefficients.amplitude_m[k]);
    append(coefficients.phase_rad[k]);
    append(coefficients.angular_frequency_rad_s[k]);
    append(coefficients.harmonic[k]);
  }
  const std::string name = deep_water_coefficients_file_name(index);
  create_output_folder(folder);
  write_bytes_atomically(folder / name, bytes);
  return {name, bytes.size(), checksum_text(bytes)};
}

DeepWaterCoefficients read_deep_water_coefficients(const std::filesystem::path& file) {
  require_readable_file(file, "a deep-water coefficient file (deep_water_cascade_<i>.bin, docs/deep-water.md)");
  const std::string bytes = read_file_bytes(file);
  const std::string subject = file.string();
  if (bytes.size() < kCoefficientHeaderBytes || bytes.compare(0, 8, std::string(kCoefficientMagic, 8)) != 0)
    throw Error(subject, "is not a nearshore deep-water coefficient file (no NSDWCOEF header)",
                "give a deep_water_cascade_<i>.bin written by nearshore bake");
  std::size_t offset = 8;
  const auto read = [&](auto& value) {
    std::memcpy(&value, bytes.data() + offset, sizeof value);
    offset += sizeof value;
  };
  std::uint32_t version = 0, n = 0;
  DeepWaterCoefficients coefficients;
  read(version);
  read(n);
  read(coefficients.tile_length_m);
  read(coefficients.loop_period_s);
  if (version != kCoefficientVersion)
    throw Error(subject, fmt::format("has format version {}; this reader knows version {}", version, kCoefficientVersion),
                "read it with the nearshore version that wrote it, or bake again");
  const std::size_t records = static_cast<std::size_t>(n) * n;
  if (n < 8 || n > 4096 || bytes.size() != kCoefficientHeaderBytes + records * kCoefficientRecordBytes)
    throw Error(subject,
                fmt::format("holds {} bytes, but a grid of N = {} needs {}", bytes.size(), n,
                            kCoefficientHeaderBytes + records * kCoefficientRecordBytes),
                "the file is truncated or corrupt: bake again (SequenceReader::verify_checksums checks it against "
                "the manifest)");
  coefficients.grid_size = static_cast<int>(n);
  coefficients.amplitude_m.resize(records);
  coefficients.phase_rad.resize(records);
  coefficients.angular_frequency_rad_s.resize(records);
  coefficients.harmonic.resize(records);
  for (std::size_t k = 0; k < records; ++k) {
    read(coefficients.amplitude_m[k]);
    read(coefficients.phase_rad[k]);
    read(coefficients.angular_frequency_rad_s[k]);
    read(coefficients.harmonic[k]);
  }
  return coefficients;
}

}  // namespace nearshore::sequence
