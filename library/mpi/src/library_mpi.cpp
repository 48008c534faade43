// The sea-state library under MPI: rank 0 plans and hands out states, largest first, to every rank
// that asks (itself included, on a second thread); library_mpi.hpp says why and how.
#include "nearshore/library/library_mpi.hpp"

#include <fmt/core.h>
#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <memory>
#include <map>
#include <mutex>
#include <optional>
#include <thread>

#include "nearshore/core/error.hpp"
#include "nearshore/core/progress.hpp"

namespace nearshore::library {
namespace {
namespace fs = std::filesystem;
using json = nlohmann::json;

// worker -> rank 0: {"outcome": null (first request) or the last state's outcome}
constexpr int kTagRequest = 1;
// rank 0 -> worker: {"state": index, "id": "..."} or {"stop": true}
constexpr int kTagAssign = 2;

int g_rank = 0;

void send_text(const std::string& text, int destination, int tag) {
  MPI_Send(text.data(), static_cast<int>(text.size()), MPI_CHAR, destination, tag, MPI_COMM_WORLD);
}

// The next message of `tag` from `source` (MPI_ANY_SOURCE too); `sender` receives its rank.
std::string receive_text(int source, int tag, int* sender = nullptr) {
  MPI_Status status;
  MPI_Probe(source, tag, MPI_COMM_WORLD, &status);
  int count = 0;
  MPI_Get_count(&status, MPI_CHAR, &count);
  std::string text(static_cast<std::size_t>(count), '\0');
  MPI_Recv(text.data(), count, MPI_CHAR, status.MPI_SOURCE, tag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  if (sender) *sender = status.MPI_SOURCE;
  return text;
}

// Rank 0's text to every rank (the plan's verdict).
std::string broadcast_text(std::string text) {
  long long size = static_cast<long long>(text.size());
  MPI_Bcast(&size, 1, MPI_LONG_LONG, 0, MPI_COMM_WORLD);
  text.resize(static_cast<std::size_t>(size));
  MPI_Bcast(text.data(), static_cast<int>(size), MPI_CHAR, 0, MPI_COMM_WORLD);
  return text;
}

// MPI for the length of a run: initialised once, finalised on the way out (errors included).
class MpiSession {
 public:
  MpiSession() {
    int initialised = 0;
    MPI_Initialized(&initialised);
    if (initialised) return;
    int provided = 0;
    MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
    owner_ = true;
    if (provided < MPI_THREAD_FUNNELED)
      throw Error("MPI", "does not allow a second thread beside the one that calls it (MPI_THREAD_FUNNELED)",
                  "use an MPI library built with thread support (Debian's Open MPI has it)");
  }
  ~MpiSession() {
    if (owner_) MPI_Finalize();
  }
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;

 private:
  bool owner_ = false;
};

// The ranks that share this process's machine (MPI_COMM_TYPE_SHARED).
int ranks_on_this_machine() {
  MPI_Comm machine;
  MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &machine);
  int size = 1;
  MPI_Comm_size(machine, &size);
  MPI_Comm_free(&machine);
  return size;
}

// TBB threads inside each bake: as asked, or the cores of this rank's machine divided among the
// ranks that share it (complete_library_state runs each state in an arena of that many).
int threads_per_rank(const LibraryOptions& options) {
  if (options.threads_per_rank > 0) return options.threads_per_rank;
  const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  return std::max(1, cores / ranks_on_this_machine());
}

LibrarySummary worker_summary(const fs::path& output_folder, int ranks, const std::map<std::string, int>& actions,
                              int failed, std::chrono::steady_clock::time_point start) {
  LibrarySummary summary;
  summary.output_folder = output_folder;
  summary.ranks = ranks;
  summary.actions = actions;
  summary.failed = failed;
  for (const auto& [action, count] : actions) summary.states += count;
  summary.states += failed;
  summary.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

// Ranks 1..N-1: ask, work, report, until told to stop.
LibrarySummary run_worker(const LibraryOptions& options, int ranks) {
  const auto start = std::chrono::steady_clock::now();
  std::map<std::string, int> actions;
  int failed = 0;
  json request = {{"outcome", nullptr}};
  while (true) {
    send_text(request.dump(), 0, kTagRequest);
    const json assignment = json::parse(receive_text(0, kTagAssign));
    if (assignment.contains("stop")) break;
    const LibraryStateOutcome outcome = complete_library_state(
        options.output_folder, assignment.at("state").get<int>(), assignment.at("id").get<std::string>(), g_rank, options);
    if (!outcome.action.empty()) ++actions[outcome.action];
    failed += outcome.status == sequence::LibraryStateStatus::kFailed;
    request = {{"outcome", outcome.to_json()}};
  }
  return worker_summary(options.output_folder, ranks, actions, failed, start);
}

// Rank 0: hands out the schedule to the other ranks' requests and to its own worker thread, and
// records every outcome. Only this (main) thread calls MPI.
LibrarySummary run_scheduler(LibraryPlan& plan, const LibraryOptions& options, int ranks) {
  LibraryLedger ledger(plan, options, ranks);
  std::mutex mutex;
  std::deque<int> queue(plan.schedule.begin(), plan.schedule.end());
  // Rank 0's own thread's events in order: a state started (no outcome) or finished.
  std::vector<std::pair<int, std::optional<LibraryStateOutcome>>> local_events;
  bool local_done = false;

  std::thread local([&] {
    while (true) {
      int state = -1;
      {
        const std::lock_guard<std::mutex> lock(mutex);
        if (queue.empty()) {
          local_done = true;
          return;
        }
        state = queue.front();
        queue.pop_front();
        local_events.emplace_back(state, std::nullopt);
      }
      LibraryStateOutcome outcome =
          complete_library_state(options.output_folder, state, plan.index.states[state].id, 0, options);
      const std::lock_guard<std::mutex> lock(mutex);
      local_events.emplace_back(state, std::move(outcome));
    }
  });

  int working_ranks = ranks - 1;
  bool local_running = true;
  while (working_ranks > 0 || local_running) {
    // Rank 0's own thread: what it started and finished since the last look.
    {
      const std::lock_guard<std::mutex> lock(mutex);
      for (const auto& [state, outcome] : local_events) {
        if (outcome)
          ledger.finished(*outcome);
        else
          ledger.started(state, 0);
      }
      local_events.clear();
      local_running = !local_done;
    }
    int waiting = 0;
    MPI_Status status;
    MPI_Iprobe(MPI_ANY_SOURCE, kTagRequest, MPI_COMM_WORLD, &waiting, &status);
    if (!waiting) {
      // Polled, not blocked: a blocking receive would leave rank 0's own outcomes unrecorded until
      // another rank spoke. 20 ms is nothing next to a bake and costs no measurable CPU.
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
      continue;
    }
    int sender = 0;
    const json request = json::parse(receive_text(status.MPI_SOURCE, kTagRequest, &sender));
    if (!request.at("outcome").is_null())
      ledger.finished(LibraryStateOutcome::from_json(request.at("outcome"), fmt::format("rank {}'s message", sender)));
    int state = -1;
    {
      const std::lock_guard<std::mutex> lock(mutex);
      if (!queue.empty()) {
        state = queue.front();
        queue.pop_front();
      }
    }
    if (state < 0) {
      send_text(json{{"stop", true}}.dump(), sender, kTagAssign);
      --working_ranks;
      continue;
    }
    ledger.started(state, sender);
    send_text(json{{"state", state}, {"id", plan.index.states[state].id}}.dump(), sender, kTagAssign);
  }
  local.join();
  return ledger.summary();
}

}  // namespace

bool started_by_mpi_launcher() {
  for (const char* variable : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"})
    if (std::getenv(variable)) return true;
  return false;
}

int library_mpi_rank() { return g_rank; }

LibrarySummary run_library_mpi(const fs::path& library_file, const LibraryOptions& options) {
  const MpiSession session;
  int ranks = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &g_rank);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  ProgressBar::set_quiet(true);  // the library's own line (rank 0) replaces the bakes' bars
  LibraryOptions rank_options = options;
  rank_options.threads_per_rank = threads_per_rank(options);

  // 1. Rank 0 plans, holding the folder's lock; every rank learns whether it may start.
  std::optional<FolderLock> lock;
  std::optional<LibraryPlan> plan;
  json verdict = {{"ok", true}};
  if (g_rank == 0) {
    try {
      const LibraryDefinition definition = read_library_definition(library_file);
      lock.emplace(lock_library_folder(library_file, options));
      plan.emplace(plan_library(definition, options));
    } catch (const Error& error) {
      verdict = {{"ok", false}, {"subject", error.subject()}, {"problem", error.problem()}, {"fix", error.fix()}};
    }
  }
  verdict = json::parse(broadcast_text(g_rank == 0 ? verdict.dump() : std::string()));
  if (!verdict.at("ok").get<bool>())
    throw Error(verdict.at("subject").get<std::string>(), verdict.at("problem").get<std::string>(),
                verdict.at("fix").get<std::string>());

  // 2. The work. A failure of rank 0's own bookkeeping (the index cannot be written) stops every
  //    rank: the others would otherwise wait for it forever.
  if (g_rank != 0) return run_worker(rank_options, ranks);
  try {
    return run_scheduler(*plan, rank_options, ranks);
  } catch (const std::exception& error) {
    std::fprintf(stderr, "error: %s\n", error.what());
    std::fflush(stderr);
    MPI_Abort(MPI_COMM_WORLD, 1);
    throw;
  }
}

}  // namespace nearshore::library
