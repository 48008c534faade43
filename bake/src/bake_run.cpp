#include "nearshore/bake/bake_run.hpp"

#include <chrono>
#include <cmath>
#include <fstream>
#include <sstream>

#include <fmt/core.h>

#include "nearshore/bake/bake_gauges.hpp"
#include "nearshore/ocean/deep_water.hpp"
#include "nearshore/bake/deep_water_record.hpp"
#include "nearshore/boussinesq/initial_conditions.hpp"
#include "nearshore/bake/deep_water_tiles.hpp"
#include "nearshore/core/atomic_file.hpp"
#include "nearshore/core/error.hpp"
#include "nearshore/core/hash.hpp"
#include "nearshore/core/progress.hpp"
#include "nearshore/sequence/sequence_writer.hpp"

namespace nearshore::bake {

using namespace nearshore::ocean;       // spectra, sea states, the deep-water field
using namespace nearshore::boussinesq;  // the solver and its parameters
namespace fs = std::filesystem;
namespace {

// Version 2: the case fingerprint and the solver state's checksums are XXH64 (were FNV-1a).
constexpr char kCheckpointMagic[16] = "nearshore-ckpt2";
// The stability guard looks at the whole field after every step: a scan costs a few per cent of a
// step, and a blow-up caught in its first step names the cell where it starts, before the implicit
// sweeps have carried NaN along the whole row.
constexpr long kStabilityCheckSteps = 1;

// XXH64 (core/hash.hpp) of the canonical dump of the case document: a checkpoint only resumes the
// case it was written for (the solver itself also checks grid, dt and its parameters on load).
std::uint64_t case_fingerprint(const BakeCase& bake_case) {
  return xxh64(bake_case.source.dump() + fmt::format("|dt={:.17g}", bake_case.solver.time_step_s));
}

struct StepPlan {
  long total = 0, first_frame = 0, per_frame = 1, per_gauge = 1, per_checkpoint = 0;
};

StepPlan plan_steps(const BakeCase& bake_case) {
  const double dt = bake_case.solver.time_step_s;
  const BakeTiming& timing = bake_case.timing;
  StepPlan plan;
  plan.total = std::lround(timing.duration_s / dt);
  plan.first_frame = std::lround(timing.spin_up_s / dt);
  plan.per_frame = std::max(1L, std::lround(timing.output_interval_s / dt));  // exact: resolve_time_step
  plan.per_gauge = timing.gauge_interval_s > 0 ? std::max(1L, std::lround(timing.gauge_interval_s / dt)) : 1;
  plan.per_checkpoint = timing.checkpoint_interval_s > 0 ? std::max(1L, std::lround(timing.checkpoint_interval_s / dt)) : 0;
  return plan;
}

[[noreturn]] void report_instability(const BakeCase& bake_case, const InstabilityReport& report, const fs::path& checkpoint,
                                     double checkpoint_time_s) {
  const std::string kept = checkpoint_time_s >= 0
                               ? fmt::format("the last good checkpoint (t = {:.3f} s) is kept in {}", checkpoint_time_s, checkpoint.string())
                               : std::string("no checkpoint had been written yet");
  throw Error(bake_case.case_file.string(),
              fmt::format("the solver became unstable at t = {:.3f} s in cell (column {}, row {}) at x = {:.2f} m, y = {:.2f} m, "
                          "still-water depth {:.3f} m: {} (value {:.4g})",
                          report.time_s, report.column, report.row, report.x_m, report.y_m, report.depth_m, report.what, report.value),
              fmt::format("reduce time.courant_number or time.time_step_s (now {:.5g} s), smooth the bathymetry near that cell "
                          "or raise solver.dispersion_cutoff_depth_m, or lower solver.breaking.onset_celerity_fraction (now {}) so "
                          "waves break earlier; {}",
                          bake_case.solver.time_step_s, bake_case.solver.breaking.onset_celerity_fraction, kept));
}

void write_checkpoint(const fs::path& file, std::uint64_t fingerprint, const BoussinesqSolver& solver,
                      const GaugeRecorder& gauges) {
  write_file_atomically(file, [&](const fs::path& temporary) {
    std::ofstream out(temporary, std::ios::binary);
    out.write(kCheckpointMagic, sizeof kCheckpointMagic);
    out.write(reinterpret_cast<const char*>(&fingerprint), sizeof fingerprint);
    gauges.save(out);
    solver.save_state(out);
    out.flush();
    if (!out) throw Error(temporary.string(), "could not be written completely", "check free disk space");
  });
}

void read_checkpoint(const fs::path& file, std::uint64_t fingerprint, BoussinesqSolver& solver, GaugeRecorder& gauges) {
  const std::string subject = file.string();
  if (!fs::exists(file))
    throw Error(subject, "does not exist, so there is nothing to resume", "bake again from the start (BakeOptions::resume = false)");
  std::ifstream in(file, std::ios::binary);
  char magic[sizeof kCheckpointMagic] = {};
  std::uint64_t stored = 0;
  const bool magic_read = static_cast<bool>(in.read(magic, sizeof magic));
  if (magic_read && std::string(magic) == "nearshore-ckpt1")
    throw Error(subject, "is a checkpoint of an older nearshore (version 1, FNV-1a fingerprints)",
                "bake again from the start (BakeOptions::resume = false)");
  if (!magic_read || std::string(magic, sizeof magic) != std::string(kCheckpointMagic, sizeof magic))
    throw Error(subject, "is not a nearshore bake checkpoint", "delete it and bake again from the start (BakeOptions::resume = false)");
  if (!in.read(reinterpret_cast<char*>(&stored), sizeof stored) || stored != fingerprint)
    throw Error(subject, "was written for a different case file or time step",
                "bake again from the start, BakeOptions::resume = false (a checkpoint only continues the exact case that wrote it)");
  gauges.load(in, subject);
  solver.load_state(in);
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
          {"outputs",
           {{"folder", output_folder.string()},
            {"frames", frames},
            {"first_frame_time_s", first_frame_time_s},
            {"frame_interval_s", frame_interval_s},
            {"gauges_csv", gauges_csv.string()}}},
          {"deep_water", deep_water}};
}

BakeSummary run_bake(const BakeCase& bake_case, const BakeOptions& options) {
  const auto wall_start = std::chrono::steady_clock::now();
  const fs::path& folder = options.output_folder;
  create_output_folder(folder);
  const fs::path checkpoint = checkpoint_path(folder);
  const StepPlan plan = plan_steps(bake_case);
  const std::uint64_t fingerprint = case_fingerprint(bake_case);

  BoussinesqSolver solver(bake_case.harbour, bake_case.solver, bake_case.wave_maker);
  GaugeRecorder gauges(bake_case.gauges);
  BakeSummary summary;
  summary.time_step_s = solver.time_step_s();
  if (options.resume) {
    read_checkpoint(checkpoint, fingerprint, solver, gauges);
    summary.resumed_from_s = solver.time_s();
  } else {
    std::error_code ignored;
    fs::remove(checkpoint, ignored);  // a stale checkpoint of an earlier run must never be resumed
    if (bake_case.solitary_wave) start_solitary_wave(solver, bake_case.harbour, *bake_case.solitary_wave);
  }
  double checkpoint_time_s = options.resume ? solver.time_s() : -1.0;

  sequence::SequenceDescription description;
  description.frame_interval_s = plan.per_frame * summary.time_step_s;
  description.first_frame_time_s = plan.first_frame * summary.time_step_s;
  description.wave_conditions = bake_case.wave_conditions;
  description.seed = bake_case.wave_maker.sea_state.seed;
  description.loop_period_s = bake_case.wave_maker.sea_state.loop_period_s;
  description.solver = bake_case.solver_record;
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
        write_checkpoint(checkpoint, fingerprint, solver, gauges);
      });
      checkpoint_time_s = solver.time_s();
    }
  };

  ProgressBar progress("baking", plan.total * summary.time_step_s, "s");
  const long first_step = solver.step_count();
  if (!options.resume) outputs_at(0);
  const auto stepping_start = std::chrono::steady_clock::now();
  while (solver.step_count() < plan.total) {
    solver.step();
    outputs_at(solver.step_count());
    progress.update(solver.time_s(), fmt::format("t = {:.2f} s", solver.time_s()));
  }
  const double stepping_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - stepping_start).count();
  const long last_frame = frame_index_at(plan.total - (plan.total - plan.first_frame) % plan.per_frame);
  summary.frames = static_cast<int>(last_frame + 1);
  gauges.write_csv(folder / "gauges.csv");
  writer.finish(summary.frames);
  progress.finish(fmt::format("{} frames", summary.frames));
  std::error_code ignored;
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
  summary.deep_water = std::move(deep_water_summary_json);
  return summary;
}

}  // namespace nearshore::bake
