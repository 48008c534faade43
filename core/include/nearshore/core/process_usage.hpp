#pragma once
// What this process and this machine are using, as Linux reports it (proc(5), getrusage(2),
// clock_gettime(2)): the timers and the load every benchmark reports beside its figures
// (bench/, `nearshore bench`), and the resident set a bake's peak memory is measured by.
#include <chrono>
#include <optional>
#include <string>

namespace nearshore {

/// Wall seconds from `start` to now (steady clock).
inline double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// CPU seconds of the calling thread (CLOCK_THREAD_CPUTIME_ID): the timer of per-frame costs, which
/// wall time on a shared machine would blur.
double thread_cpu_s();

/// User + system CPU seconds of every thread of the process (getrusage RUSAGE_SELF).
double process_cpu_s();

/// The 1-, 5- and 15-minute load averages of /proc/loadavg.
struct LoadAverage {
  double one_minute = 0.0, five_minutes = 0.0, fifteen_minutes = 0.0;
};
/// nullopt where /proc/loadavg cannot be read.
std::optional<LoadAverage> load_average();

/// The first line of /proc/loadavg as it stands ("1.02 0.87 0.66 2/345 6789"); empty where it
/// cannot be read.
std::string proc_loadavg_line();

/// VmRSS of /proc/self/status: the resident set now, bytes (0 where the kernel does not say).
double resident_set_bytes();
/// VmHWM of /proc/self/status: the peak resident set, bytes (0 where the kernel does not say).
double peak_resident_set_bytes();
/// Resets the peak resident set (VmHWM) to the current one (Linux >= 4.0, proc(5) clear_refs "5"),
/// so that a measured stage's peak is its own. False where the kernel does not allow it.
bool reset_peak_resident_set();

}  // namespace nearshore
