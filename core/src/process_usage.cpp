#include "nearshore/core/process_usage.hpp"

#include <sys/resource.h>
#include <time.h>

#include <cstdio>
#include <fstream>

namespace nearshore {
namespace {

// A "Key:  1234 kB" line of /proc/self/status, bytes.
double status_bytes(const std::string& key) {
  std::ifstream file("/proc/self/status");
  std::string name;
  while (file >> name) {
    double kib = 0.0;
    if (name == key + ":" && file >> kib) return kib * 1024.0;
    std::getline(file, name);
  }
  return 0.0;
}

}  // namespace

double thread_cpu_s() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

double process_cpu_s() {
  struct rusage usage {};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
}

std::optional<LoadAverage> load_average() {
  LoadAverage load;
  std::FILE* file = std::fopen("/proc/loadavg", "r");
  if (file == nullptr) return std::nullopt;
  const int read = std::fscanf(file, "%lf %lf %lf", &load.one_minute, &load.five_minutes, &load.fifteen_minutes);
  std::fclose(file);
  if (read != 3) return std::nullopt;
  return load;
}

std::string proc_loadavg_line() {
  std::string line;
  std::getline(std::ifstream("/proc/loadavg"), line);
  return line;
}

double resident_set_bytes() { return status_bytes("VmRSS"); }

double peak_resident_set_bytes() { return status_bytes("VmHWM"); }

bool reset_peak_resident_set() {
  std::ofstream file("/proc/self/clear_refs");
  file << "5";
  return static_cast<bool>(file);
}

}  // namespace nearshore
