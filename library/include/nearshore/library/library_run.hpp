#pragma once
// Baking a sea-state library (docs/library.md): every state of LIBRARY.toml's sweep into its own
// sequence folder, with its loop tables, and the index (sequence/library_index.hpp) beside them:
//
//   DIR/library.json      the index, rewritten atomically after every state
//   DIR/cases/<id>.json   the case each state is baked from (the base case with its keys set)
//   DIR/states/<id>/      the state's sequence: manifest.json, frames, depth.exr, gauges.csv,
//                         loops.json, loops_gram.bin (and checkpoint.bin while it bakes)
//
// The work is split in four parts that a serial run and the MPI scheduler (library_mpi.hpp) share:
//   plan_library            rank 0: the cases written, their cost (cells x steps) and the schedule,
//                           largest first;
//   complete_library_state  any rank: one state made complete (reused when its sequence verifies
//                           and its loop tables belong to it, resumed from its checkpoint, or baked);
//   LibraryLedger           rank 0: outcomes into the index, and the progress line;
//   run_library             serial: the three in one loop.
// Resuming is the same call as starting: a state counts as done when its manifest's checksums
// verify and its loops.json names that manifest's checksum; only the others are baked.
#include <chrono>
#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "nearshore/core/folder_lock.hpp"
#include "nearshore/library/library_definition.hpp"
#include "nearshore/sequence/library_index.hpp"

namespace nearshore::library {

/// The sub-folders of a library folder.
inline constexpr const char* kCasesFolder = "cases";
inline constexpr const char* kStatesFolder = "states";

struct LibraryOptions {
  std::filesystem::path output_folder;
  /// Bake again the states whose case has changed since they were baked (a changed base case or
  /// library file); without it such a library folder is refused untouched.
  bool overwrite = false;
  /// Print a line on stderr for every state started and finished (states done/total, ETA, what
  /// every rank does). The bakes' own progress bars are silenced during a library run.
  bool progress = true;
  /// TBB threads inside each bake: 0 = every core of this rank's machine divided among the ranks
  /// that share it (all of them when serial).
  int threads_per_rank = 0;
  /// Called on the rank that does the work, before (finished = false) and after each state: for
  /// hosts that show their own progress, and for the fault tests (tests/library/).
  std::function<void(const std::string& state_id, bool finished)> on_state;
};

/// What one rank did with one state (sent to rank 0 as JSON under MPI).
struct LibraryStateOutcome {
  int state = -1;  ///< index into the plan's states
  std::string id;
  sequence::LibraryStateStatus status = sequence::LibraryStateStatus::kPending;
  std::string action;  ///< "reused", "loops", "resumed", "baked" (LibraryIndex::Run::action); "" when it failed early
  std::string manifest_checksum, loops_checksum;
  std::string error;
  int rank = 0;
  double wall_time_s = 0.0;
  nlohmann::json to_json() const;
  /// Throws nearshore::Error naming `source` when the JSON is not an outcome.
  static LibraryStateOutcome from_json(const nlohmann::json& value, const std::string& source);
};

struct LibraryPlan {
  LibraryDefinition definition;
  std::filesystem::path output_folder;
  sequence::LibraryIndex index;  ///< every state: pending, or failed when its case was refused
  std::vector<int> schedule;     ///< the pending states, largest cost first (ties: library order)
};

/// Rank 0, holding the folder's lock: reads the definition's states, writes DIR/cases/<id>.json
/// (only those that changed), reads each case to price it (cells x solver steps; a case the reader
/// refuses makes a failed state, not an error), removes the temporary files of killed writers, and
/// writes the index with every state pending. Refuses (nearshore::Error naming the folder) a folder
/// whose cases differ from this library's unless LibraryOptions::overwrite, which then invalidates
/// those states (their manifest, loop tables and checkpoint) before anything else is written.
LibraryPlan plan_library(const LibraryDefinition& definition, const LibraryOptions& options);

/// Any rank: makes state `id` of the library in `output_folder` complete and says how. Never
/// throws for the state's own problems (a bake that fails, an unstable solver, a full disk): they
/// are the outcome's error.
LibraryStateOutcome complete_library_state(const std::filesystem::path& output_folder, int state,
                                           const std::string& id, int rank, const LibraryOptions& options);

/// The summary of a run (what `nearshore library --json` prints).
struct LibrarySummary {
  std::filesystem::path output_folder, index_file;
  int states = 0, baked = 0, failed = 0, pending = 0;
  std::map<std::string, int> actions;  ///< "reused", "loops", "resumed", "baked" -> count
  int ranks = 1;
  double wall_time_s = 0.0;
  /// States made this run (baked or resumed) per hour of wall time: the throughput
  /// `nearshore bench library` compares between rank counts.
  double states_per_hour = 0.0;
  nlohmann::json to_json() const;
};

/// Rank 0's record of a run: outcomes into the index (rewritten after each), the progress line.
class LibraryLedger {
 public:
  LibraryLedger(LibraryPlan& plan, const LibraryOptions& options, int ranks);
  void started(int state, int rank);
  void finished(const LibraryStateOutcome& outcome);
  LibrarySummary summary() const;

 private:
  void print_progress() const;
  LibraryPlan& plan_;
  const LibraryOptions& options_;
  int ranks_;
  std::chrono::steady_clock::time_point start_;
  std::vector<int> busy_;          ///< per rank: the state it works on, -1 idle
  std::vector<int> done_by_rank_;  ///< per rank: states finished
  double made_cost_ = 0.0;         ///< cost of the states baked or resumed so far
  std::map<std::string, int> actions_;
};

/// `nearshore library LIBRARY.toml -o DIR` on one process: the states one after another, every
/// core inside each bake. Holds DIR's lock (folder_lock.hpp) for the whole run.
LibrarySummary run_library(const std::filesystem::path& library_file, const LibraryOptions& options);

/// The lock a library run holds on its folder (created first), named for the messages of others.
FolderLock lock_library_folder(const std::filesystem::path& library_file, const LibraryOptions& options);

}  // namespace nearshore::library
