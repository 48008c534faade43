// _nearshore: the compiled half of the Python module `nearshore` (docs/python.md). Thin on purpose:
// every function calls the library the CLI or the C API calls and turns its results into NumPy
// arrays (without a copy where the library already holds them: an array's base owns the raster)
// and its nearshore::Error into nearshore.Error with the library's message. No physics here.
//
// Surface queries take the road of the C API's nearshore_sea_query_at (capi/src/nearshore_c.cpp,
// c_boundary.hpp): StreamingEngine::snapshot_at(t), then SurfaceSampler::states at the points,
// so the values equal the C API's (which rounds them to float) bit for bit: tests/python holds it.
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "nearshore/bake/bake_case.hpp"
#include "nearshore/bake/bake_gauges.hpp"
#include "nearshore/bake/bake_run.hpp"
#include "nearshore/bake/structure_layers.hpp"
#include "nearshore/bathymetry/harbour_builder.hpp"
#include "nearshore/core/error.hpp"
#include "nearshore/core/geo_position.hpp"
#include "nearshore/export/export_sequence.hpp"
#include "nearshore/library/library_run.hpp"
#include "nearshore/library/operability.hpp"
#include "nearshore/core/progress.hpp"
#include "nearshore/loops/inspector.hpp"
#include "nearshore/ocean/record_spectrum.hpp"
#include "nearshore/runtime/library_player.hpp"
#include "nearshore/runtime/streaming_engine.hpp"
#include "nearshore/runtime/surface_sampler.hpp"
#include "nearshore/sequence/library_index.hpp"
#include "nearshore/sequence/loops_file.hpp"
#include "nearshore/sequence/sequence_reader.hpp"

namespace py = pybind11;
namespace fs = std::filesystem;
using namespace nearshore;

namespace {

using InputArray = py::array_t<double, py::array::c_style | py::array::forcecast>;

// JSON as Python objects (dict, list, float, ...), through the json module: the one converter.
py::object python_of(const nlohmann::json& value) { return py::module_::import("json").attr("loads")(value.dump()); }

// A NumPy view of `values` (rows x columns, row 0 south) whose base keeps `owner` alive: no copy.
template <class T, class Owner>
py::array_t<T> view_of(const std::shared_ptr<Owner>& owner, const T* values, int columns, int rows) {
  auto* kept = new std::shared_ptr<Owner>(owner);
  py::capsule base(kept, [](void* pointer) { delete static_cast<std::shared_ptr<Owner>*>(pointer); });
  const auto row_bytes = static_cast<py::ssize_t>(columns * sizeof(T));
  return py::array_t<T>({static_cast<py::ssize_t>(rows), static_cast<py::ssize_t>(columns)},
                        {row_bytes, static_cast<py::ssize_t>(sizeof(T))}, values, base);
}

template <class T, class Owner>
py::object raster_view(const std::shared_ptr<Owner>& owner, const Raster<T>& raster) {
  if (raster.empty()) return py::none();  // a channel not read, an optional map not stored
  return view_of(owner, raster.data(), raster.columns(), raster.rows());
}

// The geometry as the manifest and depth.exr store it (core's to_json: spacing_m for square cells,
// spacing_x_m and spacing_y_m otherwise); nearshore.Geometry reads either.
py::object geometry_of(const GridGeometry& geometry) { return python_of(nlohmann::json(geometry)); }

py::dict frame_of(sequence::Frame decoded) {
  auto frame = std::make_shared<sequence::Frame>(std::move(decoded));
  py::dict out;
  out["index"] = frame->index;
  out["time_s"] = frame->time_s;
  out["surface_elevation_m"] = raster_view(frame, frame->surface_elevation_m);
  out["flux_x_m2_s"] = raster_view(frame, frame->flux_x_m2_s);
  out["flux_y_m2_s"] = raster_view(frame, frame->flux_y_m2_s);
  out["breaking"] = raster_view(frame, frame->breaking);
  return out;
}

py::dict harbour_grid_of(HarbourGrid read) {
  auto grid = std::make_shared<HarbourGrid>(std::move(read));
  py::dict out;
  out["geometry"] = geometry_of(grid->geometry);
  out["still_water_depth_m"] = raster_view(grid, grid->still_water_depth_m);
  out["land"] = raster_view(grid, grid->land);
  out["porosity"] = raster_view(grid, grid->porosity);
  out["coast_distance_m"] = raster_view(grid, grid->coast_distance_m);
  out["porous_stone_diameter_m"] = raster_view(grid, grid->porous_stone_diameter_m);
  return out;
}

// A (gauges, samples) array of per-gauge columns (the table holds one vector per gauge, so that is
// the one copy); None when the table holds no such columns (fluxes not read).
py::object gauge_columns_of(const std::vector<std::vector<double>>& columns, std::size_t gauges, py::ssize_t samples) {
  if (columns.size() != gauges) return py::none();
  py::array_t<double> out({static_cast<py::ssize_t>(gauges), samples});
  auto rows = out.mutable_unchecked<2>();
  for (std::size_t g = 0; g < gauges; ++g)
    for (py::ssize_t k = 0; k < samples; ++k) rows(static_cast<py::ssize_t>(g), k) = columns[g][k];
  return out;
}

// gauges.csv and, where given, gauge_fluxes.csv (bake_gauges.hpp): the times without a copy, the
// elevations and fluxes as (gauges, samples) arrays.
py::dict gauges_of(bake::GaugeTable read) {
  auto table = std::make_shared<bake::GaugeTable>(std::move(read));
  const auto samples = static_cast<py::ssize_t>(table->time_s.size());
  const std::size_t gauges = table->names.size();
  auto* kept = new std::shared_ptr<bake::GaugeTable>(table);
  py::capsule base(kept, [](void* pointer) { delete static_cast<std::shared_ptr<bake::GaugeTable>*>(pointer); });
  py::dict out;
  out["names"] = table->names;
  out["time_s"] = py::array_t<double>({samples}, {static_cast<py::ssize_t>(sizeof(double))}, table->time_s.data(), base);
  out["elevation_m"] = gauge_columns_of(table->elevation_m, gauges, samples);
  out["flux_x_m2_s"] = gauge_columns_of(table->flux_x_m2_s, gauges, samples);
  out["flux_y_m2_s"] = gauge_columns_of(table->flux_y_m2_s, gauges, samples);
  return out;
}

py::array_t<double> array_of(const std::vector<double>& values) { return py::array_t<double>(values.size(), values.data()); }

py::dict spectrum_of(const ocean::RecordSpectrum& s) {
  py::dict out;
  out["frequency_hz"] = array_of(s.frequency_hz);
  out["variance_density_m2_hz"] = array_of(s.variance_density_m2_hz);
  out["frequency_resolution_hz"] = s.frequency_resolution_hz;
  out["segment_samples"] = s.segment_samples;
  out["segment_count"] = s.segment_count;
  out["significant_height_hm0_m"] = s.significant_height_hm0_m;
  out["peak_period_s"] = s.peak_period_s;
  out["mean_period_tm01_s"] = s.mean_period_tm01_s;
  out["zero_crossing_period_tm02_s"] = s.zero_crossing_period_tm02_s;
  return out;
}


std::span<const double> record_of(const InputArray& record, const char* name) {
  if (record.ndim() != 1) throw Error("record spectrum", fmt::format("{} is not one-dimensional", name), "pass one record");
  return {record.data(), static_cast<std::size_t>(record.size())};
}

ocean::RecordSpectrumOptions spectrum_options(int segment_samples, double min_frequency_hz, double max_frequency_hz) {
  ocean::RecordSpectrumOptions options;
  options.segment_samples = segment_samples;
  options.min_frequency_hz = min_frequency_hz;
  options.max_frequency_hz = max_frequency_hz;
  return options;
}

sequence::ChannelSelection channels_of(const std::vector<std::string>& names) {
  sequence::ChannelSelection selected{false, false, false, false};
  for (const std::string& name : names) {
    if (name == "surface_elevation") selected.surface_elevation = true;
    else if (name == "flux_x") selected.flux_x = true;
    else if (name == "flux_y") selected.flux_y = true;
    else if (name == "breaking") selected.breaking = true;
    else
      throw Error("channels", fmt::format("\"{}\" is not a frame channel", name),
                  "give some of \"surface_elevation\", \"flux_x\", \"flux_y\", \"breaking\"");
  }
  return selected;
}

// A display time (runtime::is_display_time, the C API's rule too).
void checked_time(double time_s) {
  if (!runtime::is_display_time(time_s))
    throw Error("time_s", fmt::format("{:.6g} is outside 0 - {:g} s", time_s, runtime::kLatestDisplayTime_s),
                "give a display time of the sea's timeline (time 0 is the first step of its plan)");
}

// A streamed sea: what nearshore_sea_open opens (runtime::PlayedSea), with the C API's defaults
// for everything Python does not set (nearshore_sea_options_init: StreamingOptions' defaults).
class Sea {
 public:
  Sea(const fs::path& folder, const std::string& conditions, const std::string& plan, std::uint64_t seed) {
    runtime::StreamingOptions options;
    const std::optional<runtime::PlanKind> kind = plan == "auto" ? runtime::PlanKind::kOptimalLoop
                                                                 : runtime::parse_plan_kind(plan);
    if (!kind)
      throw Error("plan", fmt::format("\"{}\" is not a playback plan", plan),
                  "give \"auto\", \"exact period\", \"optimal loop\", \"random walk\" or \"frame order\"");
    options.plan = *kind;
    if (seed != 0) options.seed = seed;
    played_ = std::make_unique<runtime::PlayedSea>(folder, sequence::parse_sea_conditions(conditions, "conditions"),
                                                   options);
  }

  runtime::StreamingEngine& engine() const { return played_->engine(); }

  // The SurfaceState of every point at display time `time_s` (nearshore_sea_query_at's road).
  std::vector<runtime::SurfaceState> states_at(double time_s, const InputArray& x_m, const InputArray& y_m,
                                               bool lattice) const {
    checked_time(time_s);
    if (x_m.size() != y_m.size())
      throw Error("x_m, y_m", fmt::format("{} x values but {} y values", x_m.size(), y_m.size()),
                  "give one y per x (site metres)");
    std::vector<runtime::SitePoint> points(static_cast<std::size_t>(x_m.size()));
    const double* x = x_m.data();
    const double* y = y_m.data();
    for (std::size_t i = 0; i < points.size(); ++i) {
      if (!std::isfinite(x[i]) || !std::isfinite(y[i]))
        throw Error("x_m, y_m", fmt::format("point {} ({}, {}) is not finite", i, x[i], y[i]), "give site metres");
      points[i] = {x[i], y[i]};
    }
    std::vector<runtime::SurfaceState> states(points.size());
    py::gil_scoped_release unlocked;
    const runtime::SurfaceSampler sampler(engine().snapshot_at(time_s));
    sampler.states(points, states, lattice ? runtime::ChoppyPoint::kLattice : runtime::ChoppyPoint::kDisplaced);
    return states;
  }

 private:
  std::unique_ptr<runtime::PlayedSea> played_;
};

py::dict query_at(const Sea& sea, double time_s, const InputArray& x_m, const InputArray& y_m, bool lattice) {
  const std::vector<runtime::SurfaceState> states = sea.states_at(time_s, x_m, y_m, lattice);
  const auto n = static_cast<py::ssize_t>(states.size());
  py::array_t<double> elevation(n), velocity_x(n), velocity_y(n), vertical(n), slope_x(n), slope_y(n), weight(n);
  py::array_t<double> normal({n, py::ssize_t{3}});
  py::array_t<bool> dry(n);
  double* e = elevation.mutable_data();
  double* u = velocity_x.mutable_data();
  double* v = velocity_y.mutable_data();
  double* w = vertical.mutable_data();
  double* sx = slope_x.mutable_data();
  double* sy = slope_y.mutable_data();
  double* hw = weight.mutable_data();
  double* nz = normal.mutable_data();
  bool* d = dry.mutable_data();
  for (py::ssize_t i = 0; i < n; ++i) {
    const runtime::SurfaceState& s = states[static_cast<std::size_t>(i)];
    e[i] = s.surface_elevation_m;
    u[i] = s.velocity_x_m_s;
    v[i] = s.velocity_y_m_s;
    w[i] = s.vertical_velocity_m_s;
    sx[i] = s.slope_x;
    sy[i] = s.slope_y;
    hw[i] = s.harbour_weight;
    nz[3 * i] = s.normal_x;
    nz[3 * i + 1] = s.normal_y;
    nz[3 * i + 2] = s.normal_z;
    d[i] = s.dry;
  }
  py::dict out;
  out["elevation_m"] = elevation;
  out["velocity_x_m_s"] = velocity_x;
  out["velocity_y_m_s"] = velocity_y;
  out["vertical_velocity_m_s"] = vertical;
  out["slope_x"] = slope_x;
  out["slope_y"] = slope_y;
  out["normal"] = normal;
  out["harbour_weight"] = weight;
  out["dry"] = dry;
  return out;
}

// `nearshore bake CASE -o DIR` (tools/bake_command.cpp): the same two library calls.
py::dict bake_case(const fs::path& case_file, const fs::path& output_folder, bool resume, bool overwrite,
                   bool allow_over_budget, bool progress) {
  ProgressBar::set_quiet(!progress);
  nlohmann::json printed;
  {
    py::gil_scoped_release unlocked;
    const bake::BakeCase read = bake::read_bake_case(case_file, {allow_over_budget});
    bake::BakeOptions options;
    options.output_folder = output_folder;
    options.resume = resume;
    options.overwrite = overwrite;
    options.allow_over_budget = allow_over_budget;
    printed = bake::run_bake(read, options).to_json();
    printed["warnings"] = read.warnings;
    if (!read.structure_layers.empty()) printed["structure_layers"] = bake::structure_layers_record(read.structure_layers);
  }
  return python_of(printed);
}

// What a case file says where Python wants it before or after a bake: its grid, timing and
// gauges (site metres: east and north of the grid's south-west corner, as queries take them).
py::dict read_case(const fs::path& case_file, bool allow_over_budget) {
  const bake::BakeCase read = bake::read_bake_case(case_file, {allow_over_budget});
  py::dict out;
  out["case_file"] = read.case_file;
  out["geometry"] = geometry_of(read.harbour.geometry);
  out["duration_s"] = read.timing.duration_s;
  out["spin_up_s"] = read.timing.spin_up_s;
  out["output_interval_s"] = read.timing.output_interval_s;
  out["gauge_interval_s"] = read.timing.gauge_interval_s;
  py::list gauges;
  for (const bake::GaugeSpec& gauge : read.gauges) {
    py::dict item;
    item["name"] = gauge.name;
    item["x_m"] = gauge.x_m - read.harbour.geometry.origin_x_m;
    item["y_m"] = gauge.y_m - read.harbour.geometry.origin_y_m;
    gauges.append(item);
  }
  out["gauges"] = gauges;
  out["warnings"] = read.warnings;
  out["wave_conditions"] = python_of(read.wave_conditions);
  return out;
}

// `nearshore loops SEQUENCE` (tools/loops_command.cpp) with its option defaults; the report as
// `--json` prints it. Writes loops.json unless write_tables is false.
py::dict analyse_loops(const fs::path& sequence_folder, double loop_s, std::vector<double> lengths_s,
                       double max_crossfade_s, double period_crossfade_s, bool recompute, bool verify, bool write_tables,
                       double memory_mb, int threads, bool progress) {
  ProgressBar::set_quiet(!progress);
  loops::LoopsOptions analysis;
  analysis.recompute = recompute;
  analysis.verify = verify;
  analysis.write_tables = write_tables;
  analysis.report_lengths_s = std::move(lengths_s);
  analysis.requested_loop_s = loop_s;
  analysis.max_crossfade_s = max_crossfade_s;
  // As on the command line, 0 means hard cuts (the library reads 0 as "keep the frames' count").
  if (max_crossfade_s == 0) analysis.transitions.max_crossfade_frames = 0;
  analysis.period_crossfade_s = period_crossfade_s;
  analysis.gram.memory_budget_bytes = static_cast<std::size_t>(memory_mb * (1 << 20));
  analysis.gram.threads = threads;
  nlohmann::json report;
  {
    py::gil_scoped_release unlocked;
    report = loops::analyse_loops(sequence_folder, analysis).to_json();
  }
  return python_of(report);
}


// The library names its options structs' fields in errors and warnings; Python users set them as
// the keyword arguments below, as tools/ puts its flags in their place (command_support.hpp
// naming_flags_in_errors).
std::string with_keywords(std::string message) {
  static const std::pair<const char*, const char*> kKeywords[] = {
      {"BakeOptions::resume", "resume=True"},
      {"BakeOptions::overwrite", "overwrite=True"},
      {"BakeOptions::allow_over_budget", "allow_over_budget=True"},
      {"CaseReadOptions::allow_over_budget", "allow_over_budget=True"},
      {"BakeOptions::output_folder", "output_folder"},
      // nearshore.bathy's keywords for BathyRequest's fields (tools/bathy_command.cpp names its flags)
      {"BathyRequest::spacing_m", "spacing_m"},
      {"BathyRequest::bbox_lon_lat", "bbox"},
      {"BathyRequest::bbox_projected_m", "bbox_m"},
      {"BathyRequest::sign", "sign"},
      {"ReadOptions::sign", "sign"},
      {"DepthSign::kPositiveDown", "sign=\"depth\""},
      {"DepthSign::kPositiveUp", "sign=\"elevation\""},
      {"BathyRequest::text_crs", "xyz_crs"},
      {"ReadOptions::text_crs", "xyz_crs"},
      {"BathyRequest::projection", "projection"},
      {"BathyRequest::structure_styles", "structures"},
      {"BathyRequest::water_level_m", "water_level_m"},
      {"BathyRequest::minimum_depth_m", "min_depth_m"},
      {"BathyRequest::maximum_slope", "max_slope"},
      {"BathyRequest::land_elevation_m", "land_elevation_m"},
      {"BathyRequest::fill_uncovered_from_nearest", "fill_uncovered=True"},
      {"BathyRequest::coastline_band_m", "coastline_band_m"},
      {"BathyRequest::leave_one_out", "leave_one_out=True"},
      {"BathyRequest::surroundings_margin_m", "surroundings_margin_m"},
      {"write_bathymetry_outputs(folder)", "output_folder"},
      {"LibraryOptions::output_folder", "output_folder"},
      {"LibraryOptions::overwrite", "overwrite=True"},
      {"LibraryOptions::threads_per_rank", "threads"},
      {"OperabilityRequest::limit_significant_wave_height_m", "threshold_hs_m"},
      {"ExportRequest::frames", "frames"},
      {"ExportRequest::format", "to"},
      {"ExportRequest::output_folder", "output_folder"},
      {"ExportRequest::sequence_folder", "sequence_folder"},
      {"AgitationOptions::incident_significant_wave_height_m", "incident_hs_m"}};
  for (const auto& [field, keyword] : kKeywords)
    for (std::size_t at = message.find(field); at != std::string::npos; at = message.find(field, at))
      message.replace(at, std::string_view(field).size(), keyword);
  return message;
}

// `nearshore bathy INPUTS --spacing S -o DIR` (tools/bathy_command.cpp) with its options as keyword
// arguments: the same library calls (build_harbour_grid, write_bathymetry_outputs, the marks placed
// by core's position parser). Returns summary.json as `--json` prints it; the warnings are in it.
py::dict bathy_grid(const std::vector<fs::path>& inputs, const fs::path& output_folder, double spacing_m,
                    std::optional<std::array<double, 4>> bbox, std::optional<std::array<double, 4>> bbox_m,
                    const std::string& sign, const std::string& projection, const std::string& xyz_crs,
                    const std::map<std::string, std::pair<double, double>>& structures, double water_level_m,
                    double min_depth_m, double max_slope, double land_elevation_m, double coastline_band_m,
                    bool fill_uncovered, bool leave_one_out, const std::vector<std::pair<std::string, std::string>>& marks,
                    bool progress, double surroundings_margin_m) {
  ProgressBar::set_quiet(!progress);
  bathymetry::BathyRequest request;
  request.inputs = inputs;
  request.spacing_m = spacing_m;
  request.bbox_lon_lat = bbox;
  request.bbox_projected_m = bbox_m;
  if (sign == "depth") request.sign = bathymetry::DepthSign::kPositiveDown;
  else if (sign == "elevation") request.sign = bathymetry::DepthSign::kPositiveUp;
  else if (sign != "auto")
    throw Error("sign", fmt::format("\"{}\" is not a sign convention", sign),
                "give \"auto\" (from the files' metadata), \"depth\" (positive down) or \"elevation\" (positive up)");
  request.projection = projection;
  request.text_crs = xyz_crs;
  for (const auto& [name, width_and_porosity] : structures) {  // as --structure NAME=WIDTH_M:POROSITY sets it
    bathymetry::StructureStyle style;
    style.crest_width_m = width_and_porosity.first;
    style.porosity = width_and_porosity.second;
    request.structure_styles[name] = style;
  }
  request.water_level_m = water_level_m;
  request.minimum_depth_m = min_depth_m;
  request.maximum_slope = max_slope;
  request.land_elevation_m = land_elevation_m;
  request.coastline_band_m = coastline_band_m;
  request.leave_one_out = leave_one_out;
  request.fill_uncovered_from_nearest = fill_uncovered;
  if (!(surroundings_margin_m < 0 || (surroundings_margin_m >= 0 && surroundings_margin_m <= 1e6)))
    throw Error(fmt::format("surroundings_margin_m = {}", surroundings_margin_m), "is not a margin in metres",
                "give 0 .. 1e6 m (0: no surroundings), or None for the grid's longer side");
  request.surroundings_margin_m = surroundings_margin_m;
  nlohmann::json summary;
  {
    py::gil_scoped_release unlocked;
    const bathymetry::BathyResult result = bathymetry::build_harbour_grid(request);
    std::vector<bathymetry::PreviewMark> placed;
    for (const auto& [name, position] : marks) {
      const std::string subject = fmt::format("marks[\"{}\"]", name);
      placed.push_back({name, place_in_grid(parse_geo_position(position, subject), result.grid.geometry, subject, "the mark")});
    }
    summary = bathymetry::write_bathymetry_outputs(output_folder, result, coastline_band_m, placed);
  }
  return python_of(summary);
}

// `nearshore library LIBRARY.toml -o DIR [--overwrite] [--threads N]` (tools/library_command.cpp),
// serial (an MPI run is the CLI's, under mpirun). Returns the summary `--json` prints; a state that
// failed (the others are baked) raises, as the CLI exits 2, naming the states and their errors.
py::dict library_run(const fs::path& library_file, const fs::path& output_folder, bool overwrite, int threads,
                     bool progress) {
  library::LibraryOptions options;
  options.output_folder = output_folder;
  options.overwrite = overwrite;
  options.threads_per_rank = threads;
  options.progress = progress;
  ProgressBar::set_quiet(!progress);
  library::LibrarySummary summary;
  {
    py::gil_scoped_release unlocked;
    summary = library::run_library(library_file, options);
  }
  if (summary.failed > 0) {
    std::string failed;
    for (const sequence::LibraryIndex::State& state : sequence::read_library_index(summary.output_folder).states)
      if (state.status == sequence::LibraryStateStatus::kFailed) failed += fmt::format("; {}: {}", state.id, state.error);
    throw Error(summary.index_file.string(),
                fmt::format("{} of {} states failed (the others are baked){}", summary.failed, summary.states, failed),
                "fix what each error names and run the library again (finished states are kept)");
  }
  return python_of(summary.to_json());
}

// `nearshore library operability LIB --occurrence F --berths F --threshold-hs H [-o DIR] [--hold C]`.
py::dict library_operability(const fs::path& library_folder, const fs::path& occurrence, const fs::path& berths,
                             double threshold_hs_m, const fs::path& output_folder, const std::string& hold) {
  library::OperabilityRequest request;
  request.library_folder = library_folder;
  request.occurrence_file = occurrence;
  request.berths_file = berths;
  request.limit_significant_wave_height_m = threshold_hs_m;
  request.held = sequence::parse_sea_conditions(hold, "hold");
  nlohmann::json out;
  {
    py::gil_scoped_release unlocked;
    const library::OperabilityResult result = library::compute_operability(request);
    out = result.to_json();
    if (!output_folder.empty()) {
      nlohmann::json files = nlohmann::json::array();
      for (const fs::path& file : library::write_operability(result, output_folder)) files.push_back(file.string());
      out["files"] = files;
    }
  }
  return python_of(out);
}

// `nearshore export SEQ --to FORMAT -o DIR [--frames A:B] [--incident-hs H] [--berths F]`
// (tools/export_command.cpp). `frames` is (first, end) with end -1 for the last; the summary as
// `--json` prints it.
py::dict export_run(const fs::path& sequence_folder, const std::string& to, const fs::path& output_folder,
                    std::pair<int, int> frames, double incident_hs_m, const fs::path& berths, bool progress) {
  ProgressBar::set_quiet(!progress);
  exports::ExportRequest request;
  request.sequence_folder = sequence_folder;
  request.output_folder = output_folder;
  request.format = exports::parse_export_format(to);
  request.frames = {frames.first, frames.second};
  if (incident_hs_m > 0.0) request.agitation.incident_significant_wave_height_m = incident_hs_m;
  request.agitation.berths_file = berths;
  if (request.format != exports::ExportFormat::kAgitation && (incident_hs_m > 0.0 || !berths.empty()))
    throw Error("incident_hs_m, berths", "belong to to=\"agitation\"", "leave them out for this format");
  nlohmann::json summary;
  {
    py::gil_scoped_release unlocked;
    summary = exports::export_sequence(request).to_json();
  }
  return python_of(summary);
}

}  // namespace

PYBIND11_MODULE(_nearshore, m) {
  m.doc() = "nearshore's library calls for Python; use the package `nearshore` (docs/python.md)";
  // Every library error keeps its message (the file or object at fault, the problem, the fix), with
  // the options' fields named as the keyword arguments that set them (with_keywords).
  static py::exception<Error> error_type(m, "Error", PyExc_RuntimeError);
  py::register_exception_translator([](std::exception_ptr thrown) {
    try {
      if (thrown) std::rethrow_exception(thrown);
    } catch (const Error& error) {

      PyErr_SetString(error_type.ptr(), with_keywords(error.what()).c_str());
    }
  });

  py::class_<sequence::SequenceReader, std::shared_ptr<sequence::SequenceReader>>(m, "SequenceReader")
      .def(py::init<const fs::path&>(), py::arg("folder"))
      .def_property_readonly("folder", &sequence::SequenceReader::folder)
      .def_property_readonly("frame_count", &sequence::SequenceReader::frame_count)
      .def_property_readonly("frame_interval_s", &sequence::SequenceReader::frame_interval_s)
      .def_property_readonly("geometry", [](const sequence::SequenceReader& r) { return geometry_of(r.geometry()); })
      .def_property_readonly("manifest",
                             [](const sequence::SequenceReader& r) { return python_of(sequence::manifest_to_json(r.manifest())); })
      .def("frame_time_s", [](const sequence::SequenceReader& r, int index) { return r.manifest().frame_time_s(index); })
      .def(
          "read_frame",
          [](const sequence::SequenceReader& r, int index, const std::vector<std::string>& channels, bool verify) {
            const sequence::ChannelSelection selected = channels_of(channels);
            sequence::Frame frame;
            {
              py::gil_scoped_release unlocked;
              r.read_frame_into(index, frame, selected, verify ? sequence::Verify::kYes : sequence::Verify::kNo);
            }
            return frame_of(std::move(frame));
          },
          py::arg("index"), py::arg("channels"), py::arg("verify") = false)
      .def("read_harbour_grid", [](const sequence::SequenceReader& r) { return harbour_grid_of(r.read_harbour_grid()); })
      .def("verify_checksums", &sequence::SequenceReader::verify_checksums, py::call_guard<py::gil_scoped_release>());

  m.def("read_loops_file", [](const fs::path& folder) { return python_of(sequence::loops_file_to_json(sequence::read_loops_file(folder))); },
        py::arg("folder"));
  m.def(
      "record_spectrum",
      [](const InputArray& elevation_m, double sample_interval_s, int segment_samples, double min_frequency_hz,
         double max_frequency_hz) {
        return spectrum_of(ocean::record_spectrum(record_of(elevation_m, "elevation_m"), sample_interval_s,
                                                  spectrum_options(segment_samples, min_frequency_hz, max_frequency_hz)));
      },
      py::arg("elevation_m"), py::arg("sample_interval_s"), py::arg("segment_samples") = 0,
      py::arg("min_frequency_hz") = 0.0, py::arg("max_frequency_hz") = 0.0);
  m.def(
      "directional_record_spectrum",
      [](const InputArray& elevation_m, const InputArray& flux_x, const InputArray& flux_y, double sample_interval_s,
         int segment_samples, double min_frequency_hz, double max_frequency_hz) {
        const ocean::DirectionalRecordSpectrum s = ocean::directional_record_spectrum(
            record_of(elevation_m, "elevation_m"), record_of(flux_x, "flux_x"), record_of(flux_y, "flux_y"),
            sample_interval_s, spectrum_options(segment_samples, min_frequency_hz, max_frequency_hz));
        py::dict out = spectrum_of(s.elevation);
        out["a1"] = array_of(s.a1);
        out["b1"] = array_of(s.b1);
        out["direction_deg"] = array_of(s.direction_deg);
        out["spread_deg"] = array_of(s.spread_deg);
        out["peak_direction_deg"] = s.peak_direction_deg;
        out["mean_direction_deg"] = s.mean_direction_deg;
        out["directional_spread_deg"] = s.directional_spread_deg;
        return out;
      },
      py::arg("elevation_m"), py::arg("flux_x"), py::arg("flux_y"), py::arg("sample_interval_s"),
      py::arg("segment_samples") = 0, py::arg("min_frequency_hz") = 0.0, py::arg("max_frequency_hz") = 0.0);
  m.def(
      "read_gauges_csv",
      [](const fs::path& file, const fs::path& fluxes_file) {
        bake::GaugeTable table = bake::read_gauges_csv(file);
        if (!fluxes_file.empty()) bake::read_gauge_fluxes_csv(fluxes_file, table);
        return gauges_of(std::move(table));
      },
      py::arg("file"), py::arg("fluxes_file") = fs::path());

  py::class_<Sea>(m, "Sea")
      .def(py::init<const fs::path&, const std::string&, const std::string&, std::uint64_t>(), py::arg("folder"),
           py::arg("conditions") = "", py::arg("plan") = "auto", py::arg("seed") = 0)
      .def_property_readonly("geometry", [](const Sea& sea) { return geometry_of(sea.engine().manifest().geometry); })
      .def_property_readonly("frame_interval_s", [](const Sea& sea) { return sea.engine().frame_interval_s(); })
      .def_property_readonly("plan", [](const Sea& sea) { return sea.engine().stats().plan; })
      .def("query_at", &query_at, py::arg("time_s"), py::arg("x_m"), py::arg("y_m"), py::arg("lattice") = false)
      .def(
          "harbour_elevation_at",
          [](const Sea& sea, double time_s) {
            checked_time(time_s);
            const GridGeometry& geometry = sea.engine().manifest().geometry;
            py::array_t<float> out({static_cast<py::ssize_t>(geometry.rows), static_cast<py::ssize_t>(geometry.columns)});
            float* values = out.mutable_data();
            {
              py::gil_scoped_release unlocked;
              runtime::shown_harbour_elevation(sea.engine().snapshot_at(time_s), values);
            }
            return out;
          },
          py::arg("time_s"));

  m.def("bake", &bake_case, py::arg("case_file"), py::arg("output_folder"), py::arg("resume") = false,
        py::arg("overwrite") = false, py::arg("allow_over_budget") = false, py::arg("progress") = false);
  m.def("bathy", &bathy_grid, py::arg("inputs"), py::arg("output_folder"), py::arg("spacing_m"), py::arg("bbox"),
        py::arg("bbox_m"), py::arg("sign"), py::arg("projection"), py::arg("xyz_crs"), py::arg("structures"),
        py::arg("water_level_m"), py::arg("min_depth_m"), py::arg("max_slope"), py::arg("land_elevation_m"),
        py::arg("coastline_band_m"), py::arg("fill_uncovered"), py::arg("leave_one_out"), py::arg("marks"),
        py::arg("progress"), py::arg("surroundings_margin_m"));
  m.def("library", &library_run, py::arg("library_file"), py::arg("output_folder"), py::arg("overwrite"),
        py::arg("threads"), py::arg("progress"));
  m.def("operability", &library_operability, py::arg("library_folder"), py::arg("occurrence"), py::arg("berths"),
        py::arg("threshold_hs_m"), py::arg("output_folder"), py::arg("hold"));
  m.def("export", &export_run, py::arg("sequence_folder"), py::arg("to"), py::arg("output_folder"), py::arg("frames"),
        py::arg("incident_hs_m"), py::arg("berths"), py::arg("progress"));
  m.def("with_keywords", &with_keywords, py::arg("message"));
  m.def("read_case", &read_case, py::arg("case_file"), py::arg("allow_over_budget") = false);
  m.def("loops", &analyse_loops, py::arg("sequence_folder"), py::arg("loop_s") = 0.0,
        py::arg("lengths_s") = std::vector<double>{10, 20, 30, 60, 120, 300}, py::arg("max_crossfade_s") = 2.0,
        py::arg("period_crossfade_s") = 10.0, py::arg("recompute") = false, py::arg("verify") = false,
        py::arg("write_tables") = true, py::arg("memory_mb") = 1024.0, py::arg("threads") = 2, py::arg("progress") = false);
}
