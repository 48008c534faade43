#include "nearshore/bake/bake_run.hpp"

#include <fcntl.h>
#include <sys/resource.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <sstream>
#include <streambuf>

#include <fmt/core.h>

#include "nearshore/bake/bake_estimate.hpp"
#include "nearshore/bake/bake_gauges.hpp"
#include "nearshore/bake/wave_statistics.hpp"
#include "nearshore/ocean/deep_water.hpp"
#include "nearshore/bake/deep_water_record.hpp"
#include "nearshore/boussinesq/initial_conditions.hpp"
#include "nearshore/bake/deep_water_tiles.hpp"
#include "nearshore/core/atomic_file.hpp"
#include "nearshore/core/atomic_stream.hpp"
#include "nearshore/core/output_folder.hpp"
#include "nearshore/core/error.hpp"
#include "nearshore/core/folder_lock.hpp"
#include "nearshore/core/hash.hpp"
#include "nearshore/core/progress.hpp"
#include "nearshore/sequence/sequence_writer.hpp"

namespace nearshore::bake {

using namespace nearshore::ocean;       // spectra, sea states, the deep-water field
using namespace nearshore::boussinesq;  // the solver and its parameters
namespace fs = std::filesystem;
namespace {

// Version 2: the case fingerprint and the solver state's checksums are XXH64 (were FNV-1a).
// Version 3: the wave statistics (wave_statistics.hpp) follow the solver state, so a resumed bake
// maps the whole run.
// Version 4: the solver's physics revision (kSolverPhysicsRevision) follows the fingerprint, so a bake
// is only resumed by a solver that computes what its first part was computed with.
// Version 5: the gauges' fluxes (P, Q) follow their elevations (gauge_fluxes.csv, the directions).
constexpr char kCheckpointMagic[16] = "nearshore-ckpt5";
// The stability guard looks at the whole field after every step: a scan costs a few per cent of a
// step, and a blow-up caught in its first step names the cell where it starts, before the implicit
// sweeps have carried NaN along the whole row.
constexpr long kStabilityCheckSteps = 1;

// XXH64 (core/hash.hpp) of the canonical dump of the case document, the time step and the solver's
// parameters as the case reader resolved them: a checkpoint only resumes the case it was written
// for, with the same parameters, those the reader derives from the grid where the file leaves them
// out included (the wet/dry threshold, the effective-depth limit), so a build that derives one
// otherwise does not continue another build's bake. (The solver itself also checks grid, dt and
// equations on load.)
std::uint64_t case_fingerprint(const BakeCase& bake_case) {
  return xxh64(bake_case.source.dump() + fmt::format("|dt={:.17g}|", bake_case.solver.time_step_s) +
               bake_case.solver_record.dump());
}

struct StepPlan {
  long total = 0, first_frame = 0, per_frame = 1, per_gauge = 1, per_checkpoint = 0;
  long frames = 0;  ///< frames of the whole bake
};

// Counts beyond these are no bake but a mistyped duration or step (duration_s = 1e20 once
// overflowed std::lround into a negative step count, emptied the folder and failed at finish()):
// steps must stay exact in a double, and frame names hold 8 digits (sequence_format.hpp).
constexpr double kMostSteps = 1e15;
constexpr long kMostFrames = 99'999'999;

// The maps of every step after spin-up, beside the frames (docs/formats/wave-statistics.md).
constexpr const char* kWaveStatisticsFile = "wave_statistics.tif";
constexpr const char* kRunupLineFile = "wave_statistics_runup.geojson";  // its run-up line as lines

StepPlan plan_steps(const BakeCase& bake_case) {
  const double dt = bake_case.solver.time_step_s;
  const BakeTiming& timing = bake_case.timing;
  const std::string subject = bake_case.case_file.string();
  const auto steps_in = [&](double interval_s, const char* key) {
    const double steps = interval_s / dt;
    if (!std::isfinite(steps) || steps > kMostSteps)
      throw Error(subject, fmt::format("key `time.{}` = {:g} s is {:.3g} time steps of {:.5g} s, more than a bake can count ({:g})",
                                       key, interval_s, steps, dt, kMostSteps),
                  fmt::format("give time.{} in seconds of simulated time (a bake lasts minutes to hours)", key));
    return std::lround(steps);
  };
  StepPlan plan;
  plan.total = steps_in(timing.duration_s, "duration_s");
  plan.first_frame = steps_in(timing.spin_up_s, "spin_up_s");
  plan.per_frame = std::max(1L, steps_in(timing.output_interval_s, "output_interval_s"));  // exact: resolve_time_step
  plan.per_gauge = timing.gauge_interval_s > 0 ? std::max(1L, steps_in(timing.gauge_interval_s, "gauge_interval_s")) : 1;
  plan.per_checkpoint =
      timing.checkpoint_interval_s > 0 ? std::max(1L, steps_in(timing.checkpoint_interval_s, "checkpoint_interval_s")) : 0;
  // A checkpoint writes and flushes the whole solver state: by estimate about one step's time (the
  // solver updates ~1e7 cells a second, docs/solver.md; the state is ~100 B a cell, written at
  // ~1 GB/s), plus an fsync. One every step (accepted silently before, issue 44) doubles the bake
  // and wears the disk; every kFewestStepsPerCheckpoint steps costs a tenth at most, and a resume
  // still loses less than a second of simulated time.
  constexpr long kFewestStepsPerCheckpoint = 10;
  if (plan.per_checkpoint > 0 && plan.per_checkpoint < kFewestStepsPerCheckpoint)
    throw Error(subject,
                fmt::format("key `time.checkpoint_interval_s` = {:g} s is {} time step{} of {:.5g} s: a checkpoint writes the "
                            "whole solver state, about a step's time, so checkpoints fewer than {} steps apart would make "
                            "the bake mostly writing",
                            timing.checkpoint_interval_s, plan.per_checkpoint, plan.per_checkpoint == 1 ? "" : "s", dt,
                            kFewestStepsPerCheckpoint),
                fmt::format("give time.checkpoint_interval_s >= {:.3g} s (seconds to minutes are typical), or 0 for none",
                            kFewestStepsPerCheckpoint * dt));
  plan.frames = plan.total >= plan.first_frame ? (plan.total - plan.first_frame) / plan.per_frame + 1 : 0;
  if (plan.frames < 1)
    throw Error(subject, fmt::format("the bake would write no frame: frames start at time.spin_up_s = {:g} s, after "
                                     "time.duration_s = {:g} s",
                                     timing.spin_up_s, timing.duration_s),
                "make time.duration_s longer than time.spin_up_s by at least time.output_interval_s");
  if (plan.frames > kMostFrames)
    throw Error(subject, fmt::format("the bake would write {} frames (time.duration_s = {:g} s, time.output_interval_s = {:g} s), "
                                     "more than a sequence can number ({})",
                                     plan.frames, timing.duration_s, timing.output_interval_s, kMostFrames),
                "shorten time.duration_s or lengthen time.output_interval_s");
  return plan;
}

// What the output folder holds that a bake must not destroy unasked (issue 13: forgetting resume
// silently deleted a checkpoint and its frames; a failing bake emptied a good sequence first).
void refuse_to_destroy(const fs::path& folder, const BakeCase& bake_case, const BakeOptions& options) {
  // Never into the folder of a grid the case reads (overwrite or not: the bake's resampled
  // depth.exr would replace it, and later cases would silently read the coarser grid, issue 44);
  // another command's outputs (a harbour grid, a library) only with overwrite.
  std::vector<InputFolder> inputs;
  for (const fs::path& file : bake_case.input_files)
    inputs.push_back({file.parent_path(), "the grid " + file.filename().string() + " that the case reads"});
  check_output_folder(folder, OutputKind::kSequence, options.overwrite, inputs, "BakeOptions::output_folder",
                      "BakeOptions::overwrite");
  if (options.overwrite) return;
  std::error_code ec;
  if (!options.resume && fs::exists(checkpoint_path(folder), ec))
    throw Error(folder.string(),
                fmt::format("holds {}, the checkpoint of an unfinished bake, which a new bake would delete together with "
                            "its frames",
                            checkpoint_path(folder).filename().string()),
                "set BakeOptions::resume to continue that bake, or BakeOptions::overwrite to start again, or write "
                "into another folder");
  const fs::path manifest = folder / std::string(sequence::kManifestFile);
  if (!options.resume && fs::exists(manifest, ec))
    throw Error(folder.string(),
                fmt::format("holds a complete sequence ({}), which this bake would replace", manifest.filename().string()),
                "write into another folder, or set BakeOptions::overwrite to replace it");
}

// Bytes of the files in `folder` that a bake rewrites: their space comes back as it goes.
double replaced_bytes(const fs::path& folder) {
  double bytes = 0;
  std::error_code ec;
  for (const auto& item : fs::directory_iterator(folder, ec)) {
    const std::string name = item.path().filename().string();
    const bool replaced = (name.starts_with("frame_") && name.ends_with(".exr")) ||
                          item.path() == checkpoint_path(folder) || name == "gauges.csv" || name == kGaugeFluxesFile ||
                          name == kGaugeStatisticsFile || name == kWaveStatisticsFile ||
                          name == std::string(sequence::kHarbourGridFile);
    std::error_code size_error;
    if (replaced && item.is_regular_file(size_error)) bytes += static_cast<double>(item.file_size(size_error));
  }
  return bytes;
}

[[noreturn]] void report_instability(const BakeCase& bake_case, const InstabilityReport& report, const fs::path& checkpoint,
                                     double checkpoint_time_s) {
  const std::string kept = checkpoint_time_s >= 0
                               ? fmt::format("the last good checkpoint (t = {:.3f} s) is kept in {}", checkpoint_time_s, checkpoint.string())
                               : std::string("no checkpoint had been written yet");
  // The breaking closure's own remedy: the eddy viscosity's onset, or for the roller (which adds no
  // dissipation) a stronger grid-scale filter against the surf zone's short waves (docs/validation.md,
  // "The surface roller": stable at full resolution with order 4).
  const auto& breaking = bake_case.solver.breaking;
  const std::string breaking_remedy =
      breaking.model == BreakingParameters::Model::kRoller
          ? fmt::format("or filter the surf zone's short waves harder with the roller (solver.shapiro_filter_order = 4, now {})",
                        bake_case.solver.shapiro_filter_order)
          : fmt::format("or lower solver.breaking.onset_celerity_fraction (now {}) so waves break earlier",
                        breaking.onset_celerity_fraction);
  // The grid-scale filter's known limit at walls (docs/solver.md, "Grid-scale filter"): from still
  // water with noise, a square pier's corners grew a mode along its faces on cells of 0.7 and 0.5 of
  // the depth (a cylinder of square cells on a fifth of it blew up within 8 s with waves), and the
  // noise decayed on cells as long as the depth. The advice starts at 0.7.
  constexpr double kWallModeSpacingPerDepth = 0.7;
  const double finest_spacing_m = bake_case.harbour.geometry.smaller_spacing_m();
  // A narrow flume's own mode (docs/solver.md, "Modes across a narrow flume"): a flux mode across a
  // flume a few cells wide grew under steep shoaling waves on cells of a tenth of the depth, at a
  // rate that halves with the time step; a flume one cell across has no such mode and gives a 1-D
  // experiment the same waves (Hansen & Svendsen, three cells and one: the same figures). There
  // every cell is beside a wall, and the wall advice would mislead: without the filter Hansen &
  // Svendsen on six cells across blew up at 23.7 s instead of 64.8 s.
  constexpr int kNarrowFlumeCells = 8;
  const int cells_across = std::min(bake_case.harbour.geometry.columns, bake_case.harbour.geometry.rows);
  const bool narrow_flume = cells_across > 1 && cells_across <= kNarrowFlumeCells;
  const std::string flume_remedy =
      narrow_flume ? fmt::format("; the grid is {} cells across: a 1-D flume needs one (a profile's bathymetry.width_m = its spacing), "
                                 "across which no mode can grow (docs/solver.md, \"Modes across a narrow flume\")",
                                 cells_across)
                   : std::string();
  const std::string filter_remedy =
      !narrow_flume && bake_case.solver.shapiro_filter_order > 0 && finest_spacing_m <= kWallModeSpacingPerDepth * report.depth_m
          ? fmt::format("; if the cell is near a wall or shore drawn in square cells, set solver.shapiro_filter_order = 0 (now {}): "
                        "on cells finer than {:.2g} of the depth the grid-scale filter can destabilise the water beside a wall "
                        "(docs/solver.md, \"Grid-scale filter\"), or, beside walls along the grid's lines, "
                        "solver.wall_dispersion = \"mirror_at_walls\" (docs/solver.md, \"Walls and the dispersive terms\")",
                        bake_case.solver.shapiro_filter_order, kWallModeSpacingPerDepth)
          : std::string();
  throw Error(bake_case.case_file.string(),
              fmt::format("the solver became unstable at t = {:.3f} s in cell (column {}, row {}) at x = {:.2f} m, y = {:.2f} m, "
                          "still-water depth {:.3f} m: {} (value {:.4g})",
                          report.time_s, report.column, report.row, report.x_m, report.y_m, report.depth_m, report.what, report.value),
              fmt::format("reduce time.courant_number or time.time_step_s (now {:.5g} s), smooth the bathymetry near that cell "
                          "or raise solver.dispersion_cutoff_depth_m, {}{}{}; {}",
                          bake_case.solver.time_step_s, breaking_remedy, filter_remedy, flume_remedy, kept));
}

void write_checkpoint(const fs::path& file, std::uint64_t fingerprint, const BoussinesqSolver& solver,
                      const GaugeRecorder& gauges, const WaveStatistics* statistics) {
  // The core's stream keeps the errno of a failed write, so a checkpoint that meets a full disk
  // says so (the state writer that sees the failed stream knows no file); the checkpoint written
  // before this one, if any, is kept.
  write_stream_atomically(
      file,
      [&](std::ostream& out) {
        out.write(kCheckpointMagic, sizeof kCheckpointMagic);
        out.write(reinterpret_cast<const char*>(&fingerprint), sizeof fingerprint);
        const std::int32_t physics_revision = kSolverPhysicsRevision;
        out.write(reinterpret_cast<const char*>(&physics_revision), sizeof physics_revision);
        gauges.save(out);
        solver.save_state(out);  // throws when the stream failed: the stream knows why
        if (statistics) statistics->save(out);
      },
      "the checkpoint");
}

// The checkpoint opened and its header checked (magic, case fingerprint, the solver's physics
// revision): positioned at the gauges.
std::ifstream open_checkpoint(const fs::path& file, std::uint64_t fingerprint) {
  const std::string subject = file.string();
  // Starting again is what BakeOptions::overwrite does: without it, a bake refuses the folder that
  // holds this checkpoint (refuse_to_destroy), so "resume = false" alone was a fix that was then
  // refused (issue 44).
  const std::string start_again =
      "bake again from the start with BakeOptions::overwrite instead of BakeOptions::resume (it replaces this checkpoint "
      "and the frames written so far)";
  if (!fs::exists(file))
    throw Error(subject, "does not exist, so there is nothing to resume", "bake again from the start (BakeOptions::resume = false)");
  std::ifstream in(file, std::ios::binary);
  if (!in) {
    const int error = errno;
    throw Error(subject, fmt::format("cannot be opened: {} (errno {})", std::strerror(error), error),
                "make the checkpoint readable, or " + start_again);
  }
  char magic[sizeof kCheckpointMagic] = {};
  std::uint64_t stored = 0;
  const bool magic_read = static_cast<bool>(in.read(magic, sizeof magic));
  if (magic_read && std::string(magic) == "nearshore-ckpt1")
    throw Error(subject, "is a checkpoint of an older nearshore (version 1, FNV-1a fingerprints)",
                start_again);
  if (magic_read && std::string(magic) == "nearshore-ckpt2")
    throw Error(subject, "is a checkpoint of an older nearshore (version 2, without the wave statistics)",
                start_again);
  if (magic_read && std::string(magic) == "nearshore-ckpt3")
    throw Error(subject,
                "is a checkpoint of an older nearshore (version 3, before checkpoints recorded the solver's physics revision): "
                "its solver may have computed other physics than this one, and a bake continued from it would change "
                "physics part-way through its sequence",
                start_again + ", or resume with the nearshore build that wrote it");
  if (magic_read && std::string(magic) == "nearshore-ckpt4")
    throw Error(subject, "is a checkpoint of an older nearshore (version 4, before the gauges recorded the flux for their directions)",
                start_again + ", or resume with the nearshore build that wrote it");
  if (!magic_read || std::string(magic, sizeof magic) != std::string(kCheckpointMagic, sizeof magic))
    throw Error(subject, "is not a nearshore bake checkpoint", start_again);
  if (!in.read(reinterpret_cast<char*>(&stored), sizeof stored) || stored != fingerprint)
    throw Error(subject, "was written for a different case file, time step or solver parameters (those derived from the grid included)",
                start_again + " (a checkpoint only continues the exact case that wrote it)");
  std::int32_t physics_revision = 0;
  if (!in.read(reinterpret_cast<char*>(&physics_revision), sizeof physics_revision))
    throw Error(subject, "is truncated (it ends before the solver's physics revision)",
                start_again);
  if (physics_revision != kSolverPhysicsRevision)
    throw Error(subject,
                fmt::format("was written by a solver of physics revision {}, and this nearshore's solver is revision {} "
                            "(docs/solver.md, \"Physics revision\"): a bake continued from it would change physics part-way "
                            "through its sequence",
                            physics_revision, kSolverPhysicsRevision),
                start_again + ", or resume with the nearshore build that wrote it");
  return in;
}

void read_checkpoint(const fs::path& file, std::uint64_t fingerprint, BoussinesqSolver& solver, GaugeRecorder& gauges,
                     WaveStatistics* statistics) {
  const std::string subject = file.string();
  std::ifstream in = open_checkpoint(file, fingerprint);
  gauges.load(in, subject);
  try {
    solver.load_state(in);
  } catch (const Error& error) {  // the solver reads a stream and knows no file: name it here
    throw Error(subject, error.subject() + " " + error.problem(), error.fix());
  }
  if (statistics) statistics->load(in, subject);
}

// How the deep-water field sits on the harbour grid and meets the bake (docs/deep-water.md,
// "Coherence"): the manifest's deep_water.coupling, for the runtime.
sequence::DeepWaterCouplingRecord deep_water_coupling(const BakeCase& bake_case) {
  sequence::DeepWaterCouplingRecord coupling;
  coupling.origin_x_m = bake_case.harbour.geometry.origin_x_m;
  coupling.origin_y_m = bake_case.harbour.geometry.origin_y_m;
  coupling.drives_wave_maker = bake_case.deep_water_maker.has_value();
  if (bake_case.deep_water_maker) {
    coupling.wave_maker = bake_case.deep_water_maker->record();
    coupling.blending = bake_case.deep_water_maker->blending.record();
  }
  return coupling;
}

// The summary's deep_water: what the runtime got and how much of the field the wave maker carries.
nlohmann::json deep_water_summary(const sequence::DeepWaterSection& section) {
  std::uintmax_t bytes = 0;
  for (const sequence::DeepWaterCascadeRecord& cascade : section.cascades)
    if (cascade.coefficients) bytes += cascade.coefficients->bytes;
  const nlohmann::json recorded = sequence::deep_water_section_to_json(section);
  nlohmann::json summary = {{"cascades", section.cascades.size()},
                            {"grid_size", section.cascades.front().grid_size},
                            {"significant_wave_height_m", section.significant_wave_height_m},
                            {"coefficients_bytes", bytes},
                            {"drives_wave_maker", section.coupling && section.coupling->drives_wave_maker}};
  if (section.coupling && section.coupling->wave_maker) {
    const sequence::DeepWaterMakerRecord& maker = *section.coupling->wave_maker;
    summary["wave_maker_components"] = maker.components;
    summary["variance_fraction"] = maker.variance_fraction;
    summary["carried_significant_wave_height_m"] = maker.carried_significant_wave_height_m;
    summary["blending"] = recorded["coupling"]["blending"];
  }
  if (section.tile_set) summary["tile_set"] = recorded["tile_set"];
  return summary;
}

}  // namespace

fs::path checkpoint_path(const fs::path& output_folder) { return output_folder / "checkpoint.bin"; }

nlohmann::json BakeSummary::to_json() const {
  return {{"cells", cells},
          {"steps", total_steps},
          {"steps_this_run", steps_this_run},
          {"time_step_s", time_step_s},
          {"wall_time_s", wall_time_s},
          {"cell_updates_per_s", cell_updates_per_s},
          {"output_wall_time_s", output_wall_time_s},
          {"resumed_from_s", resumed_from_s},
          {"seed", seed},
          {"loop_period_s", loop_period_s},
          {"resources",
           {{"estimated_memory_bytes", estimated_memory_bytes},
            {"estimated_disk_bytes", estimated_disk_bytes},
            {"peak_resident_bytes", peak_resident_bytes},
            {"solver_memory_bytes", solver_memory_bytes}}},
          {"outputs",
           {{"folder", output_folder.string()},
            {"frames", frames},
            {"first_frame_time_s", first_frame_time_s},
            {"frame_interval_s", frame_interval_s},
            {"gauges_csv", gauges_csv.string()},
            {"gauge_statistics_csv", gauge_statistics_csv.empty() ? nlohmann::json() : nlohmann::json(gauge_statistics_csv.string())},
            {"wave_statistics", wave_statistics}}},
          {"deep_water", deep_water}};
}

BakeSummary run_bake(const BakeCase& bake_case, const BakeOptions& options) {
  const auto wall_start = std::chrono::steady_clock::now();
  const fs::path& folder = options.output_folder;
  const fs::path checkpoint = checkpoint_path(folder);
  // 1. The whole plan is checked before anything is allocated or the folder touched: a bake that
  //    cannot finish must not first destroy what the folder holds.
  const StepPlan plan = plan_steps(bake_case);
  const BakeResourceEstimate estimate = estimate_bake_resources(bake_case, options.resume);
  if (!options.allow_over_budget) check_bake_resources(bake_case, estimate, folder, replaced_bytes(folder));
  const std::uint64_t fingerprint = case_fingerprint(bake_case);
  // 2. One writer per folder, for the whole run (released when run_bake returns or throws, and by
  //    the kernel when the process is killed).
  create_output_folder(folder);
  const FolderLock lock(folder, "baking " + bake_case.case_file.string());
  refuse_to_destroy(folder, bake_case, options);
  if (options.resume) open_checkpoint(checkpoint, fingerprint);  // one that cannot resume stops here, nothing removed
  // 3. Writers killed in this folder left their temporary files; nobody else writes here now.
  remove_stale_temporary_files(folder);
  remove_stale_temporary_files(folder / "deep_water_tiles");
  std::error_code ignored;
  // The folder is being rewritten: it must not look complete while it is (SequenceWriter also
  // removes the manifest, but the deep-water files below are written before it opens).
  fs::remove(folder / std::string(sequence::kManifestFile), ignored);

  BoussinesqSolver solver(bake_case.harbour, bake_case.solver, bake_case.wave_maker);
  GaugeRecorder gauges(bake_case.gauges);
  std::optional<WaveStatistics> statistics;
  if (bake_case.output.wave_statistics) statistics.emplace(bake_case.harbour, bake_case.solver.dry_depth_m);
  WaveStatistics* statistics_or_null = statistics ? &*statistics : nullptr;
  BakeSummary summary;
  summary.time_step_s = solver.time_step_s();
  // A tide ([tide] level_m, docs/solver.md "Tides"): the still-water level at the end of each step
  // is set before it; a loaded state already holds its level's water.
  const bool tide = !bake_case.tide_level.time_s.empty();
  if (options.resume) {
    read_checkpoint(checkpoint, fingerprint, solver, gauges, statistics_or_null);
    summary.resumed_from_s = solver.time_s();
    if (tide)
      solver.set_still_water_level(interpolated_elevation_m(bake_case.tide_level, solver.time_s()),
                                   BoussinesqSolver::LevelChange::kStateHoldsIt);
  } else {
    fs::remove(checkpoint, ignored);  // a stale checkpoint of an earlier run must never be resumed
    if (bake_case.solitary_wave) start_solitary_wave(solver, bake_case.harbour, *bake_case.solitary_wave);
    if (tide) solver.set_still_water_level(interpolated_elevation_m(bake_case.tide_level, 0.0));
  }
  double checkpoint_time_s = options.resume ? solver.time_s() : -1.0;

  sequence::SequenceDescription description;
  description.frame_interval_s = plan.per_frame * summary.time_step_s;
  description.first_frame_time_s = plan.first_frame * summary.time_step_s;
  description.wave_conditions = bake_case.wave_conditions;
  description.seed = bake_case.wave_maker.sea_state.seed;
  description.loop_period_s = bake_case.wave_maker.sea_state.loop_period_s;
  description.solver = bake_case.solver_record;
  description.encoding = bake_case.output.frame_encoding;
  if (bake_case.deep_water) {
    // What the runtime needs to synthesise the sea beyond the baked domain (docs/deep-water.md):
    // the cascades' coefficients beside the frames, their description in the manifest.
    try {
      DeepWaterField field(*bake_case.deep_water);
      sequence::DeepWaterSection section = describe_deep_water_field(field);
      write_deep_water_coefficient_files(field, folder, section);
      section.coupling = deep_water_coupling(bake_case);
      if (bake_case.deep_water_tile_set_frame_interval_s > 0) {
        const int frames_per_loop = static_cast<int>(
            std::lround(bake_case.deep_water->loop_period_s / bake_case.deep_water_tile_set_frame_interval_s));
        const TileSetSummary tiles =
            write_deep_water_tile_set(field, bake_case.deep_water_tile_set_cascade, frames_per_loop, folder / "deep_water_tiles");
        section.tile_set = sequence::DeepWaterTileSetRecord{"deep_water_tiles", bake_case.deep_water_tile_set_cascade,
                                                            tiles.frame_count, tiles.frame_interval_s, tiles.bytes};
      }
      description.deep_water = std::move(section);
    } catch (const Error& error) {
      throw Error(bake_case.case_file.string(), "[deep_water] " + error.problem(), error.fix());
    }
  }
  nlohmann::json deep_water_summary_json =
      description.deep_water ? deep_water_summary(*description.deep_water) : nlohmann::json();
  sequence::SequenceWriter writer(folder, bake_case.harbour, description, options.resume);

  Raster<float> flux_x, flux_y;
  double output_s = 0.0;  // wall time spent writing frames, gauges and checkpoints
  const auto timed = [&output_s](const auto& write) {
    const auto start = std::chrono::steady_clock::now();
    write();
    output_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  const auto frame_index_at = [&](long step) -> long {
    if (step < plan.first_frame || (step - plan.first_frame) % plan.per_frame != 0) return -1;
    return (step - plan.first_frame) / plan.per_frame;
  };
  // Everything that happens after the solver reached step `step`: gauges, guard, frame, checkpoint.
  const auto outputs_at = [&](long step) {
    const long frame = frame_index_at(step);
    const bool checkpoint_due = plan.per_checkpoint > 0 && step > 0 && step % plan.per_checkpoint == 0 && step < plan.total;
    if (step % plan.per_gauge == 0) gauges.record(solver.time_s(), solver);
    // Every step from the first frame on, before a checkpoint that must hold it.
    if (statistics && step >= plan.first_frame) statistics->add_step(solver.surface_elevation_m());
    if (step % kStabilityCheckSteps == 0 || frame >= 0 || checkpoint_due || step == plan.total)
      if (const auto report = solver.check_stability()) report_instability(bake_case, *report, checkpoint, checkpoint_time_s);
    if (frame >= 0) {
      solver.cell_centred_fluxes(flux_x, flux_y);
      sequence::FrameFields fields;
      fields.surface_elevation_m = &solver.surface_elevation_m();
      fields.flux_x_m2_s = &flux_x;
      fields.flux_y_m2_s = &flux_y;
      fields.breaking = &solver.breaking_indicator();
      timed([&] { writer.write_frame(static_cast<int>(frame), fields); });
    }
    if (checkpoint_due) {
      timed([&] {
        gauges.write_csv(folder / "gauges.csv");  // a killed run still leaves the gauges up to here
        gauges.write_fluxes_csv(folder / kGaugeFluxesFile);
        write_checkpoint(checkpoint, fingerprint, solver, gauges, statistics_or_null);
      });
      checkpoint_time_s = solver.time_s();
    }
  };

  // A resumed bake starts from its checkpoint's time: its ETA is projected from the steps it takes.
  ProgressBar progress("baking", plan.total * summary.time_step_s, "s", solver.time_s());
  const long first_step = solver.step_count();
  if (!options.resume) outputs_at(0);
  const auto stepping_start = std::chrono::steady_clock::now();
  while (solver.step_count() < plan.total) {
    if (tide) solver.set_still_water_level(interpolated_elevation_m(bake_case.tide_level, solver.time_s() + solver.time_step_s()));
    solver.step();
    outputs_at(solver.step_count());
    progress.update(solver.time_s(), fmt::format("t = {:.2f} s", solver.time_s()));
  }
  const double stepping_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - stepping_start).count();
  summary.frames = static_cast<int>(plan.frames);
  gauges.write_csv(folder / "gauges.csv");
  gauges.write_fluxes_csv(folder / kGaugeFluxesFile);
  // The sea state at each gauge over the frames' span (from the spin-up on); a bake whose gauges
  // hold too short a record for a spectrum (16 samples) writes none, rather than failing at its end.
  fs::path gauge_statistics_csv;
  if (!bake_case.gauges.empty() && gauge_sample_count_from(gauges.table(), bake_case.timing.spin_up_s) >= 16) {
    gauge_statistics_csv = folder / kGaugeStatisticsFile;
    timed([&] {
      write_gauge_statistics_csv(gauge_statistics_csv,
                                 gauge_statistics(gauges.table(), bake_case.gauges, bake_case.timing.spin_up_s));
    });
  } else {
    fs::remove(folder / kGaugeStatisticsFile, ignored);  // one of an earlier bake would describe another sea
  }
  nlohmann::json statistics_json;
  if (statistics) {
    timed([&] {
      write_wave_statistics_geotiff(folder / kWaveStatisticsFile, *statistics, bake_case.harbour.geometry,
                                    description.first_frame_time_s, solver.time_s());
      write_runup_line_geojson(folder / kRunupLineFile, *statistics, bake_case.harbour.geometry,
                               description.first_frame_time_s, solver.time_s());
    });
    statistics_json = {{"file", (folder / kWaveStatisticsFile).string()},
                       {"runup_line_file", (folder / kRunupLineFile).string()},
                       {"steps", statistics->step_count()}};
    if (const auto runup = statistics->highest_runup())
      statistics_json["runup"] = {{"water_level_m", runup->water_level_m}, {"ground_elevation_m", runup->ground_elevation_m},
                                  {"x_m", runup->x_m}, {"y_m", runup->y_m}};
  } else {
    fs::remove(folder / kWaveStatisticsFile, ignored);  // a map of an earlier bake would describe another sea
    fs::remove(folder / kRunupLineFile, ignored);
  }
  writer.finish(summary.frames);
  progress.finish(fmt::format("{} frames", summary.frames));
  fs::remove(checkpoint, ignored);  // the bake is complete; the manifest marks it so

  summary.cells = static_cast<long long>(bake_case.harbour.geometry.cell_count());
  summary.total_steps = plan.total;
  summary.steps_this_run = plan.total - first_step;
  summary.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  summary.cell_updates_per_s = stepping_s > 0 ? static_cast<double>(summary.cells) * summary.steps_this_run / stepping_s : 0.0;
  summary.output_wall_time_s = output_s;
  summary.first_frame_time_s = description.first_frame_time_s;
  summary.frame_interval_s = description.frame_interval_s;
  summary.seed = description.seed;
  summary.loop_period_s = description.loop_period_s;
  summary.output_folder = folder;
  summary.gauges_csv = folder / "gauges.csv";
  summary.gauge_statistics_csv = gauge_statistics_csv;
  summary.deep_water = std::move(deep_water_summary_json);
  summary.wave_statistics = std::move(statistics_json);
  summary.estimated_memory_bytes = estimate.memory_bytes;
  summary.estimated_disk_bytes = estimate.disk_bytes;
  summary.solver_memory_bytes = static_cast<double>(solver.memory_bytes());
  struct rusage usage {};
  if (::getrusage(RUSAGE_SELF, &usage) == 0) summary.peak_resident_bytes = static_cast<double>(usage.ru_maxrss) * 1024;
  return summary;
}

}  // namespace nearshore::bake
