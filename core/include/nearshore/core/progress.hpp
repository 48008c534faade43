#pragma once
// ProgressBar: what a person watching a long bake or gridding run sees on stderr.
// On a terminal it redraws one line (at most 10 times a second) with the fraction done, the
// elapsed wall time and the ETA; in a log (not a TTY) it prints a line every 10 % instead.
#include <chrono>
#include <string>
#include <string_view>

namespace nearshore {

class ProgressBar {
 public:
  /// label: what is being done ("gridding"); total: the amount of work in `unit`s ("cells", "s").
  /// done_at_start: the work a resumed run found done (from its checkpoint); the ETA is projected
  /// from what this run has done since, not from the whole fraction.
  ProgressBar(std::string label, double total, std::string unit, double done_at_start = 0.0);
  ~ProgressBar();
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;

  /// done: work finished so far (same unit as total); detail: extra text such as "t=12.5 s".
  void update(double done, std::string_view detail = {});
  /// Prints the final line with the total wall time. Called by the destructor if not before.
  void finish(std::string_view detail = {});
  double elapsed_seconds() const;

  /// Quiet mode for tests and --json runs: nothing is printed.
  static void set_quiet(bool quiet);

 private:
  void draw(double done, std::string_view detail, bool final_line);
  std::string label_, unit_;
  double total_;
  double fraction_at_start_ = 0.0;
  std::chrono::steady_clock::time_point start_, last_draw_;
  int last_decile_ = -1;
  bool finished_ = false;
  bool terminal_ = false;
};

/// The wall time still to go when `fraction_done` of the work is done after `elapsed_s`, at the
/// rate of this run (the work from `fraction_at_start` on); NaN before any progress.
double remaining_seconds(double elapsed_s, double fraction_done, double fraction_at_start = 0.0);

/// "1 h 02 min", "3 min 05 s", "12.3 s": a duration as people read it.
std::string format_duration(double seconds);

}  // namespace nearshore
