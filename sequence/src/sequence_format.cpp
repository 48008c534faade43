#include "nearshore/sequence/sequence_format.hpp"

#include <cmath>

#include <fmt/core.h>

#include "nearshore/core/error.hpp"
#include "json_fields.hpp"

namespace nearshore::sequence {
namespace {

constexpr std::pair<Compression, std::string_view> kCompressionNames[] = {
    {Compression::kNone, "none"}, {Compression::kZip, "zip"}, {Compression::kPiz, "piz"},
    {Compression::kB44, "b44"},   {Compression::kDwaa, "dwaa"}, {Compression::kRle, "rle"},
    {Compression::kZips, "zips"}, {Compression::kPxr24, "pxr24"}};

Precision parse_precision(const nlohmann::json& value, const std::string& source, const std::string& key) {
  if (value == "half") return Precision::kHalf;
  if (value == "float") return Precision::kFloat;
  throw Error(source, fmt::format("\"{}\" is {} but must be \"half\" or \"float\"", key, value.dump()),
              "rewrite the sequence with `nearshore bake`");
}

FileEntry parse_file_entry(const nlohmann::json& entry, const std::string& source, const std::string& where) {
  if (!entry.is_object())
    throw Error(source, where + " is not an object", "the manifest is corrupt; rewrite the sequence");
  FileEntry file;
  file.file = require_string(entry, "file", source);
  file.bytes = require(entry, "bytes", nlohmann::json::value_t::number_unsigned, source).get<std::uint64_t>();
  file.checksum = require_string(entry, "checksum", source);
  if (file.file.empty() || file.file.find('/') != std::string::npos || file.file.find('\\') != std::string::npos ||
      file.file == "." || file.file == "..")
    throw Error(source, fmt::format("{} names \"{}\", which is not a plain file name in the folder", where, file.file),
                "the manifest is corrupt; rewrite the sequence");
  if (file.checksum.size() != 22 || file.checksum.rfind("xxh64:", 0) != 0 ||
      file.checksum.find_first_not_of("0123456789abcdef", 6) != std::string::npos)
    throw Error(source, fmt::format("{} has checksum \"{}\", not \"xxh64:\" + 16 hex digits", where, file.checksum),
                "the manifest is corrupt; rewrite the sequence");
  return file;
}

}  // namespace

std::string_view compression_name(Compression compression) {
  for (const auto& [value, name] : kCompressionNames)
    if (value == compression) return name;
  return "unknown";
}

Compression parse_compression(std::string_view name) {
  for (const auto& [value, known] : kCompressionNames)
    if (known == name) return value;
  std::string names;
  for (const auto& [value, known] : kCompressionNames) names += (names.empty() ? "" : ", ") + std::string(known);
  throw Error(fmt::format("compression \"{}\"", name), "is not one nearshore writes", "use one of " + names);
}

const std::vector<Compression>& all_compressions() {
  static const std::vector<Compression> all = [] {
    std::vector<Compression> out;
    for (const auto& [value, name] : kCompressionNames) out.push_back(value);
    return out;
  }();
  return all;
}

std::string_view precision_name(Precision precision) { return precision == Precision::kHalf ? "half" : "float"; }

std::string frame_file_name(int index) { return fmt::format("frame_{:06d}.exr", index); }

nlohmann::json manifest_to_json(const SequenceManifest& manifest) {
  auto file_json = [](const FileEntry& file) {
    return nlohmann::json{{"file", file.file}, {"bytes", file.bytes}, {"checksum", file.checksum}};
  };
  nlohmann::json channels = nlohmann::json::array();
  const Precision precisions[4] = {manifest.encoding.surface_elevation, manifest.encoding.flux, manifest.encoding.flux,
                                   manifest.encoding.breaking};
  const char* units[4] = {"m", "m^2/s", "m^2/s", "1"};
  const char* meanings[4] = {"surface elevation eta above still water, cell centres",
                             "depth-integrated flux P along +x (east), cell centres",
                             "depth-integrated flux Q along +y (north), cell centres",
                             "breaking / foam indicator, 0 none .. 1 fully breaking"};
  for (int c = 0; c < 4; ++c)
    channels.push_back({{"name", kChannelNames[c]},
                        {"unit", units[c]},
                        {"pixel_type", precision_name(precisions[c])},
                        {"meaning", meanings[c]}});
  nlohmann::json frames = nlohmann::json::array();
  for (const FileEntry& frame : manifest.frames) frames.push_back(file_json(frame));
  return nlohmann::json{
      {"format", kManifestFormat},
      {"version", manifest.version},
      {"geometry", manifest.geometry},
      {"units", {{"length", "m"}, {"time", "s"}, {"surface_elevation", "m"}, {"flux", "m^2/s"},
                 {"depth", "m, positive down"}}},
      {"frame_count", manifest.frame_count},
      {"frame_interval_s", manifest.frame_interval_s},
      {"first_frame_time_s", manifest.first_frame_time_s},
      {"loop_period_s", manifest.loop_period_s},
      {"seed", manifest.seed},
      {"compression", compression_name(manifest.encoding.compression)},
      {"channels", channels},
      {"frame_file_pattern", "frame_{index:06d}.exr"},
      {"exr_line_order", "EXR line 0 is the northern row (Raster row rows-1)"},
      {"wave_conditions", manifest.wave_conditions},
      {"deep_water", manifest.deep_water ? deep_water_section_to_json(*manifest.deep_water) : nlohmann::json()},
      {"solver", manifest.solver},
      {"harbour_grid", file_json(manifest.harbour_grid)},
      {"frames", frames},
  };
}

SequenceManifest parse_manifest(std::string_view text, const std::string& source) {
  const nlohmann::json json = nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (json.is_discarded())
    throw Error(source, "is not valid JSON", "the manifest is truncated or corrupt; rewrite the sequence");
  if (!json.is_object()) throw Error(source, "is not a JSON object", "rewrite the sequence");
  if (require_string(json, "format", source) != kManifestFormat)
    throw Error(source, fmt::format("is not a nearshore sequence manifest (format \"{}\")", json["format"].get<std::string>()),
                "give the folder written by `nearshore bake`");
  SequenceManifest manifest;
  const double version = require_number(json, "version", source);
  if (version != kManifestVersion)
    throw Error(source, fmt::format("has format version {}, this nearshore reads version {}", version, kManifestVersion),
                "use the nearshore release that wrote it, or re-bake");
  const nlohmann::json& geometry = require(json, "geometry", nlohmann::json::value_t::object, source);
  for (const char* key : {"columns", "rows"}) {
    const double count = require_number(geometry, key, source);
    if (count < 1 || count > 65536 || count != std::floor(count))
      throw Error(source, fmt::format("\"geometry.{}\" is {}, not a cell count", key, count), "rewrite the sequence");
  }
  // Square cells carry one "spacing_m" (every manifest before issue 15); rectangular cells carry
  // "spacing_x_m" and "spacing_y_m" instead (core/src/raster.cpp, docs/formats/sequence.md).
  const bool rectangular = !geometry.contains("spacing_m") && geometry.contains("spacing_x_m");
  for (const char* key : {"origin_x_m", "origin_y_m"}) require_number(geometry, key, source);
  if (rectangular)
    for (const char* key : {"spacing_x_m", "spacing_y_m"}) require_number(geometry, key, source);
  else
    require_number(geometry, "spacing_m", source);
  try {
    manifest.geometry = geometry.get<GridGeometry>();
  } catch (const std::exception& e) {
    throw Error(source, std::string("\"geometry\" is malformed: ") + e.what(), "rewrite the sequence");
  }
  const GridGeometry& g = manifest.geometry;
  if (g.columns <= 0 || g.rows <= 0 || g.columns > 65536 || g.rows > 65536 || !(g.spacing_x_m() > 0) ||
      !std::isfinite(g.spacing_x_m()) || !(g.spacing_y_m() > 0) || !std::isfinite(g.spacing_y_m()) ||
      !std::isfinite(g.origin_x_m) || !std::isfinite(g.origin_y_m))
    throw Error(source, fmt::format("\"geometry\" is {} x {} cells of {} m x {} m, which is not a grid", g.columns, g.rows,
                                    g.spacing_x_m(), g.spacing_y_m()),
                "rewrite the sequence");
  const double frame_count = require_number(json, "frame_count", source);
  if (frame_count < 1 || frame_count > 10'000'000 || frame_count != std::floor(frame_count))
    throw Error(source, fmt::format("\"frame_count\" is {}", frame_count), "rewrite the sequence");
  manifest.frame_count = static_cast<int>(frame_count);
  manifest.frame_interval_s = require_number(json, "frame_interval_s", source);
  if (!(manifest.frame_interval_s > 0))
    throw Error(source, fmt::format("\"frame_interval_s\" is {} but must be > 0", manifest.frame_interval_s),
                "rewrite the sequence");
  manifest.first_frame_time_s = require_number(json, "first_frame_time_s", source);
  manifest.loop_period_s = require_number(json, "loop_period_s", source);
  if (manifest.loop_period_s < 0)
    throw Error(source, "\"loop_period_s\" is negative", "use 0 for a non-periodic bake");
  manifest.seed = require(json, "seed", nlohmann::json::value_t::number_unsigned, source).get<std::uint64_t>();
  try {
    manifest.encoding.compression = parse_compression(require_string(json, "compression", source));
  } catch (const Error& e) {
    throw Error(source, e.problem(), e.fix());
  }
  const nlohmann::json& channels = require(json, "channels", nlohmann::json::value_t::array, source);
  if (channels.size() != 4)
    throw Error(source, fmt::format("lists {} channels, version 1 has 4", channels.size()), "rewrite the sequence");
  Precision precisions[4];
  for (int c = 0; c < 4; ++c) {
    const nlohmann::json& channel = channels[c];
    if (!channel.is_object() || require_string(channel, "name", source) != kChannelNames[c])
      throw Error(source, fmt::format("channel {} is not \"{}\"", c, kChannelNames[c]), "rewrite the sequence");
    precisions[c] = parse_precision(require(channel, "pixel_type", nlohmann::json::value_t::string, source), source,
                                    fmt::format("channels[{}].pixel_type", c));
  }
  if (precisions[1] != precisions[2])
    throw Error(source, "flux_x and flux_y have different pixel types", "rewrite the sequence");
  manifest.encoding.surface_elevation = precisions[0];
  manifest.encoding.flux = precisions[1];
  manifest.encoding.breaking = precisions[3];
  manifest.wave_conditions = json.value("wave_conditions", nlohmann::json());
  if (const auto deep = json.find("deep_water"); deep != json.end() && !deep->is_null())
    manifest.deep_water = parse_deep_water_section(*deep, source);
  manifest.solver = json.value("solver", nlohmann::json());
  manifest.harbour_grid = parse_file_entry(require(json, "harbour_grid", nlohmann::json::value_t::object, source),
                                           source, "\"harbour_grid\"");
  const nlohmann::json& frames = require(json, "frames", nlohmann::json::value_t::array, source);
  if (frames.size() != static_cast<std::size_t>(manifest.frame_count))
    throw Error(source, fmt::format("lists {} frames but \"frame_count\" is {}", frames.size(), manifest.frame_count),
                "the manifest is corrupt; rewrite the sequence");
  manifest.frames.reserve(frames.size());
  for (std::size_t k = 0; k < frames.size(); ++k) {
    manifest.frames.push_back(parse_file_entry(frames[k], source, fmt::format("frames[{}]", k)));
    if (manifest.frames.back().file != frame_file_name(static_cast<int>(k)))
      throw Error(source, fmt::format("frames[{}] is \"{}\", expected \"{}\"", k, manifest.frames.back().file,
                                      frame_file_name(static_cast<int>(k))),
                  "the manifest is corrupt; rewrite the sequence");
  }
  return manifest;
}

}  // namespace nearshore::sequence
