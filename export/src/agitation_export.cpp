// The agitation export (`nearshore export SEQ --to agitation`, docs/commands/export.md "Agitation"):
// agitation.tif, agitation.png and, with berths, berths.csv; the numbers in the summary's JSON.
#include <cmath>
#include <sstream>

#include <fmt/core.h>

#include "export_input.hpp"
#include "nearshore/core/atomic_file.hpp"
#include "nearshore/core/error.hpp"
#include "nearshore/export/agitation.hpp"

namespace nearshore::exports {
namespace {

std::string berths_csv(const std::vector<BerthValue>& values) {
  std::ostringstream csv;
  csv << "name,x_m,y_m,longitude,latitude,significant_wave_height_m,agitation_coefficient\n";
  for (const BerthValue& value : values) {
    const Berth& b = value.berth;
    csv << b.name << ',' << fmt::format("{:.2f},{:.2f},", b.x_m, b.y_m)
        << (b.longitude_deg ? fmt::format("{:.7f},{:.7f}", *b.longitude_deg, *b.latitude_deg) : std::string(","))
        << fmt::format(",{:.4f},{:.4f}\n", value.significant_wave_height_m, value.agitation_coefficient);
  }
  return csv.str();
}

}  // namespace

void write_agitation(const ExportInput& input, ExportSummary& summary) {
  const sequence::SequenceReader& reader = input.reader;
  // 1. The incident Hs: asked for, else the wave maker's as the manifest records it.
  double incident_m = 0.0;
  std::string incident_source;
  if (input.agitation.incident_significant_wave_height_m) {
    incident_m = *input.agitation.incident_significant_wave_height_m;
    if (!(incident_m > 0.0 && std::isfinite(incident_m)))
      throw Error("AgitationOptions::incident_significant_wave_height_m", fmt::format("= {} m is not a wave height", incident_m),
                  "give the incident significant wave height in metres (> 0)");
    incident_source = "given";
  } else {
    const std::optional<double> recorded = recorded_incident_significant_wave_height_m(reader.manifest().wave_conditions);
    if (!recorded || !(*recorded > 0.0))
      throw Error(reader.folder().string(),
                  "manifest.json's wave_conditions record no wave maker height (no components, no spectrum split): the "
                  "incident Hs of the agitation coefficient is unknown",
                  "give AgitationOptions::incident_significant_wave_height_m, the significant wave height at the wave maker");
    incident_m = *recorded;
    incident_source = reader.manifest().wave_conditions.contains("spectrum_split")
                          ? "the wave maker's (manifest wave_conditions.spectrum_split.bake_significant_wave_height_m: the "
                            "baked part of the split spectrum)"
                          : "the wave maker's (manifest wave_conditions: 4 sqrt(sum a^2 / 2) over its components)";
  }
  // 2. Hs of every cell, and the ratio.
  const SignificantWaveHeight hs = sequence_significant_wave_height(reader, input.harbour, input.first_frame, input.end_frame);
  const Raster<float> coefficient = agitation_coefficient(hs.significant_wave_height_m, incident_m);
  // 3. The berths, before any file is written: a bad berths file must not leave half an export.
  std::vector<BerthValue> berths;
  if (!input.agitation.berths_file.empty()) {
    const std::vector<Berth> read = read_berths(input.agitation.berths_file, input.harbour.geometry);
    berths = berth_values(read, hs.significant_wave_height_m, incident_m, input.harbour);
  }
  if (input.harbour.geometry.crs_wkt.empty())
    summary.notes.push_back("the grid has no CRS (a laboratory frame): the GeoTIFF's coordinates are metres from its "
                            "south-west corner, without a spatial reference");
  const std::string description =
      fmt::format("Hs / incident Hs; Hs: {}; incident Hs = {:.4g} m, {}", hs.source, incident_m, incident_source);
  const std::filesystem::path tif = input.output_folder / "agitation.tif";
  write_agitation_geotiff(input, coefficient, description, tif);
  record_file(summary, tif);
  const std::filesystem::path png = input.output_folder / "agitation.png";
  write_agitation_map(input, coefficient, fmt::format("incident Hs {:.3g} m; Hs from {}", incident_m, hs.source), berths, png);
  record_file(summary, png);
  nlohmann::json berth_json = nlohmann::json::array();
  for (const BerthValue& value : berths) berth_json.push_back(berth_value_json(value));
  if (!berths.empty()) {
    const std::filesystem::path csv = input.output_folder / "berths.csv";
    write_text_atomically(csv, berths_csv(berths));
    record_file(summary, csv);
  }
  summary.agitation = {{"incident_significant_wave_height_m", incident_m},
                       {"incident_source", incident_source},
                       {"significant_wave_height_source", hs.source},
                       {"berths", berth_json}};
}

}  // namespace nearshore::exports
