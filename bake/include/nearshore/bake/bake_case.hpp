#pragma once
// A bake case: everything `nearshore bake CASE.toml -o DIR` needs, read from one TOML or JSON file
// (the same schema in both; docs/commands/bake.md documents every key with its unit).
//
// One road from the file to the solver (pbrt's single factory route): read_bake_case() parses and
// checks every key, builds the harbour grid (from a depth.exr, a 1-D flume profile or the Berkhoff
// shoal formula), and fills the solver's own SolverParameters and WaveMaker. Positions in the case
// file (gauges, source line, porous blocks) are metres from the grid's south-west corner; BakeCase
// holds them in the solver's frame (GridGeometry origin added, e.g. UTM eastings). Unknown keys are
// errors, so a typo never passes silently; every error names the case file, the key and the fix.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "nearshore/boussinesq/boussinesq_solver.hpp"
#include "nearshore/boussinesq/initial_conditions.hpp"
#include "nearshore/ocean/deep_water.hpp"
#include "nearshore/bake/bake_time_series.hpp"
#include "nearshore/bake/deep_water_coupling.hpp"
#include "nearshore/bake/structure_layers.hpp"
#include "nearshore/core/harbour_grid.hpp"
#include "nearshore/sequence/sequence_format.hpp"

namespace nearshore::bake {

/// A named point where the surface elevation is recorded every gauge interval (gauges.csv): bilinear
/// between those of the four cell centres around it that hold water (BoussinesqSolver::surface_elevation_at).
struct GaugeSpec {
  std::string name;
  double x_m = 0.0;  ///< grid frame (GridGeometry origin included), metres; the case file gives it from the SW corner
  double y_m = 0.0;
};

/// [output]: how the frames are stored and which maps the bake writes beside them
/// (docs/commands/bake.md, "[output]"; case_output.cpp reads it).
struct BakeOutput {
  /// Codec and per-channel precision of every frame (sequence_format.hpp); the manifest records
  /// both, and the bake's disk estimate counts the precision.
  sequence::FrameEncoding frame_encoding;
  /// Write DIR/wave_statistics.tif (wave_statistics.hpp): the maximum-elevation envelope, Hs, the
  /// mean level and the run-up line over every solver step after time.spin_up_s, and the run-up line
  /// as lines in DIR/wave_statistics_runup.geojson (runup_line.hpp). Off unless asked
  /// for: it holds 24 bytes per cell for the whole bake (two double sums, the float envelope, the
  /// depth), a tenth of the solver's budget of 250 B per cell (docs/solver.md "Memory", issue 15).
  bool wave_statistics = false;
};

/// Time control of a bake. All in seconds of simulated time.
struct BakeTiming {
  double duration_s = 0.0;         ///< total simulated time, spin-up included
  double spin_up_s = 0.0;          ///< frames start at this time (the field must be developed)
  double output_interval_s = 0.0;  ///< simulated time between frames; an integer number of time steps
  double checkpoint_interval_s = 0.0;  ///< 0 = no checkpoints
  double gauge_interval_s = 0.0;   ///< 0 = every time step; else an integer number of time steps
};

struct BakeCase {
  std::filesystem::path case_file;  ///< where it was read from (named in every message)
  /// The data files the case reads (a harbour grid, a local grid): a bake never writes into their
  /// folders (core/output_folder.hpp), where its resampled depth.exr would replace the grid.
  std::vector<std::filesystem::path> input_files;
  HarbourGrid harbour;              ///< the grid the solver runs on
  boussinesq::SolverParameters solver;          ///< time_step_s is always resolved (> 0): see resolve_time_step()
  boussinesq::WaveMaker wave_maker;
  /// [tide] level_m: the still-water level over the bake, metres above the grid's (the bathymetry's
  /// still_water_level_m at the start), linear between the samples; empty for none
  /// (BoussinesqSolver::set_still_water_level, docs/solver.md "Tides").
  TimeSeries tide_level;
  /// wave_maker.kind = "solitary": the solver starts from this wave instead of rest (run-up cases).
  std::optional<boussinesq::SolitaryWave> solitary_wave;
  BakeTiming timing;
  std::vector<GaugeSpec> gauges;
  /// What the case asks that is allowed but likely a mistake, in sentences naming the case file and
  /// the entry: a gauge or source line on land or outside the chart (docs/commands/bake.md,
  /// "Positions"). `nearshore bake` prints them on stderr and in its JSON summary's "warnings".
  std::vector<std::string> warnings;
  BakeOutput output;                ///< [output]: frame encoding, wave-statistics maps
  nlohmann::json wave_conditions;   ///< the wave maker as configured, recorded in the sequence
  nlohmann::json solver_record;     ///< the solver parameters as resolved, recorded in the sequence
  nlohmann::json source;            ///< the parsed case document (for the checkpoint fingerprint)
  /// [deep_water]: the FFT field the runtime shows beyond the baked domain (issue 5), made from the
  /// irregular wave maker's own spectrum, spreading, loop period and seed, or (wave_maker.kind =
  /// "deep_water") from its own spectrum and seed. The bake writes its coefficients beside the
  /// frames and its description into the manifest's `deep_water`.
  std::optional<ocean::DeepWaterSpecification> deep_water;
  /// Set when the field gives the wave maker its waves (kind "deep_water", or drive_wave_maker):
  /// which waves, the variance fraction they carry and the blending zone (deep_water_coupling.hpp).
  std::optional<CoupledWaveMaker> deep_water_maker;
  /// [deep_water] tile_set_frame_interval_s > 0: also bake cascade `deep_water_tile_set_cascade`
  /// over one loop into DIR/deep_water_tiles/ (a sequence, for engines that cannot run an FFT).
  double deep_water_tile_set_frame_interval_s = 0.0;
  int deep_water_tile_set_cascade = 0;
  /// The harbour grid's coastal structures as laid at its cells, with the porosity fitted to each
  /// one's reflection or transmission (structure_layers.hpp); recorded in solver_record["structure_layers"].
  std::vector<StructureLayer> structure_layers;
};

/// What reading a case may be told by its caller.
struct CaseReadOptions {
  /// A generated grid (kind "profile" or "berkhoff_shoal") whose bake would need more memory than
  /// the machine has (bake_estimate.hpp) is refused before the grid is allocated, unless this is set
  /// (as BakeOptions::allow_over_budget is for the run).
  bool allow_over_budget = false;
};

/// Reads and checks a case file (.toml or .json). Relative paths inside it are relative to the
/// case file's folder. Throws nearshore::Error(case file, "key `a.b` ...", fix) on any problem.
BakeCase read_bake_case(const std::filesystem::path& case_file, const CaseReadOptions& options = {});

/// The case file as a JSON document (TOML converted, integers kept apart from floats), unchecked:
/// for tools and tests that adjust a case (e.g. a coarser grid) before parse_bake_case().
nlohmann::json read_case_document(const std::filesystem::path& case_file);

/// The same from an already parsed document (tests, and JSON given in memory). `case_file` is used
/// for messages and to resolve relative paths.
BakeCase parse_bake_case(const nlohmann::json& document, const std::filesystem::path& case_file,
                         const CaseReadOptions& options = {});

/// The solver's parameters as the sequence records them (BakeCase::solver_record: the manifest's
/// `solver`, part of the checkpoint's fingerprint), from bake_case.solver, its tide and its structure
/// layers. parse_bake_case() sets solver_record from it; a tool that changes bake_case.solver after
/// reading (`nearshore bench bake`'s seed configuration) sets it again, so the sequence records what ran.
nlohmann::json solver_record_of(const BakeCase& bake_case);

/// The time step used: the requested one (time_step_s, or courant_number * dx / (|U| + sqrt(g d_max))
/// with d_max the deepest wet cell and U the imposed current, boussinesq::courant_speed_m_s), reduced to
/// the largest value that divides `output_interval_s` into a whole number of steps, so frames fall
/// exactly on steps and a periodic bake repeats exactly.
double resolve_time_step(double requested_time_step_s, double courant_number, const HarbourGrid& harbour,
                         double output_interval_s, const boussinesq::ImposedCurrent& current = {});

/// What the bake carries of the sea asked for, in words for the bake's report: the effective-depth
/// limit when one is active (docs/solver.md, "Effective depth") and an irregular sea's split between
/// the bake and the FFT deep-water layer with its Hs budget (docs/commands/bake.md, "The spectrum is
/// split"). Empty when neither applies.
std::string describe_carried_band(const BakeCase& bake_case);

/// The solver settings the case reader derived from the grid because the case file left them out
/// and that differ from the solver's own defaults, in words for the bake's report, one per line: the
/// wet/dry threshold of a grid shallower than 3 m (a 300th of its deepest water; docs/solver.md, "Wet
/// and dry") and the grid-scale filter turned off on a grid whose cells are not finer than a quarter
/// of its deepest water (docs/solver.md, "Grid-scale filter"). Empty when there is none.
std::string describe_derived_solver_settings(const BakeCase& bake_case);

/// The number of steps of `step_s` in `interval_s`, if it is a whole number (to 1e-9 relative), else -1.
long whole_steps(double interval_s, double step_s);

}  // namespace nearshore::bake
