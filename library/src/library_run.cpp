// Baking a sea-state library: plan, one state, the ledger, the serial run (library_run.hpp).
#include "nearshore/library/library_run.hpp"

#include <fmt/core.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cstdio>
#include <exception>
#include <memory>
#include <numeric>
#include <span>

#include "nearshore/bake/bake_case.hpp"
#include "nearshore/bake/bake_run.hpp"
#include "nearshore/core/atomic_file.hpp"
#include "nearshore/core/output_folder.hpp"
#include "nearshore/core/error.hpp"
#include "nearshore/core/progress.hpp"
#include "nearshore/loops/inspector.hpp"
#include "nearshore/sequence/checksum.hpp"
#include "nearshore/sequence/loops_file.hpp"
#include "nearshore/sequence/sequence_format.hpp"
#include "nearshore/sequence/sequence_reader.hpp"

namespace nearshore::library {
namespace {
namespace fs = std::filesystem;
using json = nlohmann::json;
using sequence::LibraryIndex;
using sequence::LibraryStateStatus;

std::string text_checksum(const std::string& text) { return checksum_text(std::as_bytes(std::span(text.data(), text.size()))); }
std::string file_checksum(const fs::path& file) { return text_checksum(sequence::read_file_bytes(file)); }

fs::path state_folder(const fs::path& output_folder, const std::string& id) { return output_folder / kStatesFolder / id; }
fs::path state_case(const fs::path& output_folder, const std::string& id) {
  return output_folder / kCasesFolder / (id + ".json");
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The loop tables in `folder` belong to its sequence: loops.json parses, names the checksum of the
// manifest there, and its Gram matrices file has the checksum it records. Returns loops.json's
// checksum, or "" when they do not.
std::string loops_checksum_of(const fs::path& folder, const std::string& manifest_checksum) {
  try {
    const sequence::LoopsFile tables = sequence::read_loops_file(folder);
    if (tables.sequence_manifest_checksum != manifest_checksum) return "";
    if (file_checksum(folder / tables.gram_file) != tables.gram_checksum) return "";
    return file_checksum(folder / sequence::kLoopsFileName);
  } catch (const Error&) {
    return "";
  }
}

// A complete sequence in `folder`: its manifest reads and every file it lists has its size and
// checksum. Returns the manifest's checksum, or "" when not.
std::string verified_manifest_checksum(const fs::path& folder) {
  const fs::path manifest = folder / sequence::kManifestFile;
  std::error_code ec;
  if (!fs::is_regular_file(manifest, ec)) return "";
  try {
    const sequence::SequenceReader reader(folder);
    reader.verify_checksums();
    return file_checksum(manifest);
  } catch (const Error&) {
    return "";
  }
}

// The loop tables of a complete sequence (loops/inspector.hpp with its defaults, as `nearshore
// loops SEQ` writes them): what makes the state play forever.
std::string make_loop_tables(const fs::path& folder, const std::string& manifest_checksum) {
  loops::LoopsOptions options;
  options.gram.threads = tbb::this_task_arena::max_concurrency();  // the rank's share, not 2 regardless
  loops::analyse_loops(folder, options);
  const std::string checksum = loops_checksum_of(folder, manifest_checksum);
  if (checksum.empty())
    throw Error(folder.string(), "the loop tables just written do not verify against the sequence's manifest",
                "check the disk (a file changed under the run) and run the library again");
  return checksum;
}

void remove_if_present(const fs::path& file) {
  std::error_code ec;
  fs::remove(file, ec);
  if (ec) throw Error(file.string(), "cannot be removed: " + ec.message(), "check the folder's permissions");
}

}  // namespace

// ---- outcomes -----------------------------------------------------------------------------------

json LibraryStateOutcome::to_json() const {
  return {{"state", state},
          {"id", id},
          {"status", sequence::library_state_status_name(status)},
          {"action", action},
          {"manifest_checksum", manifest_checksum},
          {"loops_checksum", loops_checksum},
          {"error", error},
          {"rank", rank},
          {"wall_time_s", wall_time_s}};
}

LibraryStateOutcome LibraryStateOutcome::from_json(const json& value, const std::string& source) {
  try {
    LibraryStateOutcome outcome;
    outcome.state = value.at("state").get<int>();
    outcome.id = value.at("id").get<std::string>();
    const std::string status = value.at("status").get<std::string>();
    outcome.status = status == "baked"    ? LibraryStateStatus::kBaked
                     : status == "failed" ? LibraryStateStatus::kFailed
                                          : LibraryStateStatus::kPending;
    outcome.action = value.at("action").get<std::string>();
    outcome.manifest_checksum = value.at("manifest_checksum").get<std::string>();
    outcome.loops_checksum = value.at("loops_checksum").get<std::string>();
    outcome.error = value.at("error").get<std::string>();
    outcome.rank = value.at("rank").get<int>();
    outcome.wall_time_s = value.at("wall_time_s").get<double>();
    return outcome;
  } catch (const json::exception& e) {
    throw Error(source, std::string("is not a state's outcome: ") + e.what(),
                "run every rank from the same nearshore build");
  }
}

// ---- the plan -----------------------------------------------------------------------------------

FolderLock lock_library_folder(const fs::path& library_file, const LibraryOptions& options) {
  if (options.output_folder.empty())
    throw Error("LibraryOptions::output_folder", "is empty", "name the folder the library is written into");
  // The output folder rules (core/output_folder.hpp): not where the library file is read from (its
  // cases and index would sit among the inputs), nor a sequence or a harbour grid unless allowed.
  check_output_folder(options.output_folder, OutputKind::kLibrary, options.overwrite,
                      {{fs::absolute(library_file).parent_path(), "the library file " + library_file.filename().string()}},
                      "LibraryOptions::output_folder", "LibraryOptions::overwrite");
  create_output_folder(options.output_folder);
  return FolderLock(options.output_folder, "building the sea-state library " + library_file.string());
}

LibraryPlan plan_library(const LibraryDefinition& definition, const LibraryOptions& options) {
  const fs::path& out = options.output_folder;
  const std::vector<LibraryStateCase> states = expand_library_states(definition);

  // 1. Which cases changed since the folder was last built: those states are stale.
  std::vector<std::string> texts;
  std::vector<bool> stale(states.size(), false), missing(states.size(), false);
  int stale_count = 0;
  for (std::size_t s = 0; s < states.size(); ++s) {
    texts.push_back(states[s].case_document.dump(2) + "\n");
    const fs::path case_file = state_case(out, states[s].id);
    std::error_code ec;
    if (!fs::exists(case_file, ec)) {
      missing[s] = true;
      continue;
    }
    stale[s] = sequence::read_file_bytes(case_file) != texts[s];
    stale_count += stale[s];
  }
  if (stale_count > 0 && !options.overwrite) {
    const auto first = std::find(stale.begin(), stale.end(), true) - stale.begin();
    throw Error(out.string(),
                fmt::format("holds {} state{} baked from other cases than this library makes (the first: {}/{}.json "
                            "differs; the base case or {} changed)",
                            stale_count, stale_count == 1 ? "" : "s", kCasesFolder, states[first].id,
                            definition.library_file.string()),
                "write the library into another folder, or set LibraryOptions::overwrite to bake "
                "those states again");
  }

  // 2. Invalidate stale states before their new case is written, so that a run killed in between
  //    never takes an old sequence for the new case's; then write the cases that changed.
  for (const char* folder : {kCasesFolder, kStatesFolder})
    create_output_folder(out / folder);
  remove_stale_temporary_files(out);
  remove_stale_temporary_files(out / kCasesFolder);
  for (std::size_t s = 0; s < states.size(); ++s) {
    if (stale[s]) {
      const fs::path folder = state_folder(out, states[s].id);
      remove_if_present(folder / sequence::kManifestFile);
      remove_if_present(folder / sequence::kLoopsFileName);
      remove_if_present(bake::checkpoint_path(folder));
    }
    if (stale[s] || missing[s]) write_text_atomically(state_case(out, states[s].id), texts[s]);
  }

  // 3. Price every state by reading its case (a refused case is a failed state), schedule the
  //    largest first: the last states to start are then the short ones, and no rank is left with
  //    a long bake while the others idle at the end.
  LibraryPlan plan;
  plan.definition = definition;
  plan.output_folder = out;
  LibraryIndex& index = plan.index;
  index.title = definition.title;
  index.library_file = definition.library_file.string();
  index.base_case = definition.base_case_as_written;
  index.axes = definition.axes;
  // Reading every case prices it (~15 ms a state, issue 44): for a large sweep, say how long that
  // takes before it starts, from the first state's pace, and how far it has come every few seconds.
  const auto planning_start = std::chrono::steady_clock::now();
  auto last_report = planning_start;
  for (std::size_t s = 0; s < states.size(); ++s) {
    if (options.progress && s > 0) {
      const auto now = std::chrono::steady_clock::now();
      const double elapsed_s = std::chrono::duration<double>(now - planning_start).count();
      const double eta_s = elapsed_s / static_cast<double>(s) * static_cast<double>(states.size() - s);
      if (s == 1 && eta_s > 2.0) {
        std::fprintf(stderr, "library: planning %zu states: reading each case, about %s (%.0f ms a state)\n",
                     states.size(), format_duration(eta_s + elapsed_s).c_str(), 1e3 * elapsed_s);
        last_report = now;
      } else if (std::chrono::duration<double>(now - last_report).count() >= 5.0) {
        std::fprintf(stderr, "library: planned %zu/%zu states, ETA %s\n", s, states.size(), format_duration(eta_s).c_str());
        last_report = now;
      }
    }
    LibraryIndex::State state;
    state.id = states[s].id;
    state.conditions = states[s].conditions;
    state.sequence = (fs::path(kStatesFolder) / state.id).string();
    state.case_file = (fs::path(kCasesFolder) / (state.id + ".json")).string();
    try {
      const bake::BakeCase bake_case = bake::read_bake_case(state_case(out, state.id));
      const double steps = std::ceil(bake_case.timing.duration_s / bake_case.solver.time_step_s - 1e-9);
      state.cost_cell_steps = static_cast<double>(bake_case.harbour.geometry.cell_count()) * steps;
    } catch (const Error& error) {
      state.status = LibraryStateStatus::kFailed;
      state.error = error.what();
    }
    index.states.push_back(std::move(state));
    if (index.states.back().status == LibraryStateStatus::kPending) plan.schedule.push_back(static_cast<int>(s));
  }
  std::stable_sort(plan.schedule.begin(), plan.schedule.end(), [&](int a, int b) {
    return index.states[a].cost_cell_steps > index.states[b].cost_cell_steps;
  });
  sequence::write_library_index(out, index);
  return plan;
}

// ---- one state ----------------------------------------------------------------------------------

namespace {
// complete_library_state on the calling thread's arena.
LibraryStateOutcome complete_state_here(const fs::path& output_folder, int state, const std::string& id, int rank,
                                        const LibraryOptions& options);
}  // namespace

LibraryStateOutcome complete_library_state(const fs::path& output_folder, int state, const std::string& id, int rank,
                                           const LibraryOptions& options) {
  // The bake's threads: as many as the rank may use, in an arena of its own (a process-wide
  // tbb::global_control would make TBB warn about the arenas the loop inspector asks for).
  if (options.threads_per_rank > 0) {
    tbb::task_arena arena(options.threads_per_rank);
    return arena.execute([&] { return complete_state_here(output_folder, state, id, rank, options); });
  }
  return complete_state_here(output_folder, state, id, rank, options);
}

namespace {

LibraryStateOutcome complete_state_here(const fs::path& output_folder, int state, const std::string& id, int rank,
                                        const LibraryOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  if (options.on_state) options.on_state(id, false);
  LibraryStateOutcome outcome;
  outcome.state = state;
  outcome.id = id;
  outcome.rank = rank;
  const fs::path folder = state_folder(output_folder, id);
  try {
    // The state's folder is this rank's alone (rank 0 holds the library's lock): what writers
    // killed in it left half-written goes first (a bake does it too; a reused state needs it).
    remove_stale_temporary_files(folder);
    // 1. A complete sequence (its manifest's checksums decide) keeps its frames; its loop tables
    //    are made again only when they do not name this manifest.
    outcome.manifest_checksum = verified_manifest_checksum(folder);
    if (!outcome.manifest_checksum.empty()) {
      outcome.loops_checksum = loops_checksum_of(folder, outcome.manifest_checksum);
      outcome.action = "reused";
      if (outcome.loops_checksum.empty()) {
        outcome.loops_checksum = make_loop_tables(folder, outcome.manifest_checksum);
        outcome.action = "loops";
      }
    } else {
      // 2. Otherwise bake: on from the checkpoint a killed bake left (the case is the same: a
      //    changed case was invalidated by plan_library), or from the start, replacing the frames
      //    of a bake killed before its first checkpoint.
      const bake::BakeCase bake_case = bake::read_bake_case(state_case(output_folder, id));
      bake::BakeOptions bake_options;
      bake_options.output_folder = folder;
      bake_options.resume = fs::exists(bake::checkpoint_path(folder));
      bake_options.overwrite = !bake_options.resume;
      bake::run_bake(bake_case, bake_options);
      outcome.manifest_checksum = verified_manifest_checksum(folder);
      if (outcome.manifest_checksum.empty())
        throw Error(folder.string(), "the sequence just baked does not verify against its manifest",
                    "check the disk (a file changed under the run) and run the library again");
      outcome.loops_checksum = make_loop_tables(folder, outcome.manifest_checksum);
      outcome.action = bake_options.resume ? "resumed" : "baked";
    }
    outcome.status = LibraryStateStatus::kBaked;
  } catch (const std::exception& error) {  // nearshore::Error, and std::bad_alloc of a huge case
    outcome.status = LibraryStateStatus::kFailed;
    outcome.error = error.what();
    outcome.manifest_checksum.clear();
    outcome.loops_checksum.clear();
  }
  outcome.wall_time_s = seconds_since(start);
  if (options.on_state) options.on_state(id, true);
  return outcome;
}

}  // namespace

// ---- the ledger ---------------------------------------------------------------------------------

LibraryLedger::LibraryLedger(LibraryPlan& plan, const LibraryOptions& options, int ranks)
    : plan_(plan), options_(options), ranks_(ranks), start_(std::chrono::steady_clock::now()),
      busy_(ranks, -1), done_by_rank_(ranks, 0) {}

void LibraryLedger::started(int state, int rank) {
  busy_.at(rank) = state;
  LibraryIndex::State& entry = plan_.index.states.at(state);
  entry.run.rank = rank;
  print_progress();
}

void LibraryLedger::finished(const LibraryStateOutcome& outcome) {
  LibraryIndex::State& entry = plan_.index.states.at(outcome.state);
  entry.status = outcome.status;
  entry.manifest_checksum = outcome.manifest_checksum;
  entry.loops_checksum = outcome.loops_checksum;
  entry.error = outcome.error;
  entry.run = {outcome.action, outcome.rank, outcome.wall_time_s};
  if (outcome.rank >= 0 && outcome.rank < ranks_) {
    busy_[outcome.rank] = -1;
    ++done_by_rank_[outcome.rank];
  }
  if (!outcome.action.empty()) ++actions_[outcome.action];
  if (outcome.action == "baked" || outcome.action == "resumed") made_cost_ += entry.cost_cell_steps;
  sequence::write_library_index(plan_.output_folder, plan_.index);
  print_progress();
}

void LibraryLedger::print_progress() const {
  if (!options_.progress) return;
  const LibraryIndex& index = plan_.index;
  const int total = static_cast<int>(index.states.size());
  const int failed = index.count(LibraryStateStatus::kFailed), baked = index.count(LibraryStateStatus::kBaked);
  // ETA from this run's throughput in cells x steps (the states differ in size; largest first).
  double remaining_cost = 0.0;
  for (const LibraryIndex::State& state : index.states)
    if (state.status == LibraryStateStatus::kPending) remaining_cost += state.cost_cell_steps;
  const double elapsed = seconds_since(start_);
  const double eta = made_cost_ > 0 ? remaining_cost * elapsed / made_cost_ : -1.0;
  std::string line = fmt::format("library: {}/{} states done ({} failed), elapsed {}, ETA {}", baked + failed, total,
                                 failed, format_duration(elapsed), remaining_cost == 0 ? "0 s" : format_duration(eta));
  for (int rank = 0; rank < ranks_; ++rank)
    line += fmt::format(" | rank {}: {} ({} done)", rank, busy_[rank] < 0 ? "idle" : index.states[busy_[rank]].id,
                        done_by_rank_[rank]);
  std::fprintf(stderr, "%s\n", line.c_str());
  std::fflush(stderr);
}

LibrarySummary LibraryLedger::summary() const {
  LibrarySummary summary;
  summary.output_folder = plan_.output_folder;
  summary.index_file = plan_.output_folder / sequence::kLibraryIndexFileName;
  summary.states = static_cast<int>(plan_.index.states.size());
  summary.baked = plan_.index.count(LibraryStateStatus::kBaked);
  summary.failed = plan_.index.count(LibraryStateStatus::kFailed);
  summary.pending = plan_.index.count(LibraryStateStatus::kPending);
  summary.actions = actions_;
  summary.ranks = ranks_;
  summary.wall_time_s = seconds_since(start_);
  const int made = (actions_.count("baked") ? actions_.at("baked") : 0) + (actions_.count("resumed") ? actions_.at("resumed") : 0);
  summary.states_per_hour = summary.wall_time_s > 0 ? made * 3600.0 / summary.wall_time_s : 0.0;
  return summary;
}

json LibrarySummary::to_json() const {
  return {{"output_folder", output_folder.string()},
          {"index", index_file.string()},
          {"states", states},
          {"baked", baked},
          {"failed", failed},
          {"pending", pending},
          {"actions", actions},
          {"ranks", ranks},
          {"wall_time_s", wall_time_s},
          {"states_per_hour", states_per_hour}};
}

// ---- serial -------------------------------------------------------------------------------------

LibrarySummary run_library(const fs::path& library_file, const LibraryOptions& options) {
  const LibraryDefinition definition = read_library_definition(library_file);
  const FolderLock lock = lock_library_folder(library_file, options);
  ProgressBar::set_quiet(true);  // the library's own line replaces the bakes' bars
  LibraryPlan plan = plan_library(definition, options);
  LibraryLedger ledger(plan, options, 1);
  for (int state : plan.schedule) {
    ledger.started(state, 0);
    ledger.finished(complete_library_state(options.output_folder, state, plan.index.states[state].id, 0, options));
  }
  return ledger.summary();
}

}  // namespace nearshore::library
