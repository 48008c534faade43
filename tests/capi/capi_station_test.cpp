// Same sea on every station (issue 40): two processes given the same sequence, plan, seed, deep
// water and display times return bit-identical queries and harbour fields. This executable runs
// itself twice at once as the two stations (posix_spawn of /proc/self/exe with
// NEARSHORE_STATION_OUTPUT set: a static initializer below then does a station's work, writes its
// bytes and exits before GoogleTest starts), and compares their files with each other and with its
// own run. What a host must share is exactly what the options below carry (docs/c-api.md).
#include "nearshore.h"
#include "capi_test_support.hpp"

#include <gtest/gtest.h>

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "nearshore/sequence/loops_file.hpp"
#include "../runtime/runtime_test_support.hpp"

extern char** environ;

namespace {
namespace fs = std::filesystem;
using namespace nearshore::capi_test;

constexpr const char* kStationOutputVariable = "NEARSHORE_STATION_OUTPUT";
constexpr const char* kStationSequenceVariable = "NEARSHORE_STATION_SEQUENCE";

// One station: open the sea as every station does (lockstep, a random walk of seed 77 with
// crossfades, a Beaufort 5 sea beyond the basin), visit the display times (with a rewind), and
// return what it saw: the samples at points over the basin and the open sea, and the harbour
// elevation array a host would upload, as raw bytes.
std::string station_bytes(const fs::path& folder) {
  nearshore_sea_options options;
  nearshore_sea_options_init(&options);
  options.plan = NEARSHORE_PLAN_RANDOM_WALK;
  options.seed = 77;
  options.beaufort_force = 5;
  options.wind_direction_deg = 200.0;
  options.time_mode = NEARSHORE_TIME_LOCKSTEP;
  nearshore_sea* sea = nullptr;
  if (nearshore_sea_open(folder.c_str(), &options, &sea) != NEARSHORE_OK) return std::string("open: ") + nearshore_last_error();
  std::vector<double> xy;
  for (double x = -40.0; x <= 200.0; x += 19.0)
    for (double y = -40.0; y <= 160.0; y += 21.0) xy.insert(xy.end(), {x, y});
  std::vector<nearshore_surface_sample> samples(xy.size() / 2);
  std::vector<float> harbour(static_cast<std::size_t>(kColumns) * kRows);
  std::string bytes;
  for (double t : {0.0, 0.4, 1.7, 3.3, 6.05, 9.9, 14.2, 2.5, 30.01}) {
    if (nearshore_sea_advance(sea, t) != NEARSHORE_OK ||
        nearshore_sea_query(sea, xy.data(), samples.size(), samples.data()) != NEARSHORE_OK ||
        nearshore_sea_copy_harbour_elevation(sea, harbour.data(), harbour.size()) != NEARSHORE_OK) {
      bytes = std::string("t = ") + std::to_string(t) + ": " + nearshore_last_error();
      break;
    }
    bytes.append(reinterpret_cast<const char*>(samples.data()), samples.size() * sizeof(nearshore_surface_sample));
    bytes.append(reinterpret_cast<const char*>(harbour.data()), harbour.size() * sizeof(float));
  }
  nearshore_stats stats;
  stats.struct_size = sizeof stats;
  if (nearshore_sea_stats(sea, &stats) == NEARSHORE_OK) bytes += std::to_string(stats.transitions_taken);
  nearshore_sea_close(sea);
  return bytes;
}

// The station side: runs before main when the parent test asked for it, then exits.
const bool kRanAsStation = [] {
  const char* output = std::getenv(kStationOutputVariable);
  const char* sequence = std::getenv(kStationSequenceVariable);
  if (!output || !sequence) return false;
  const std::string bytes = station_bytes(sequence);
  {
    std::ofstream out(std::string(output) + ".part", std::ios::binary);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  }
  std::rename((std::string(output) + ".part").c_str(), output);
  std::_Exit(0);
}();

pid_t spawn_station(const fs::path& folder, const fs::path& output) {
  std::vector<std::string> variables = {std::string(kStationOutputVariable) + "=" + output.string(),
                                        std::string(kStationSequenceVariable) + "=" + folder.string()};
  std::vector<char*> environment;
  for (std::string& v : variables) environment.push_back(v.data());
  for (char** e = environ; *e; ++e) environment.push_back(*e);
  environment.push_back(nullptr);
  std::string self = "/proc/self/exe";
  char* arguments[] = {self.data(), nullptr};
  pid_t pid = -1;
  if (posix_spawn(&pid, "/proc/self/exe", nullptr, nullptr, arguments, environment.data()) != 0) return -1;
  return pid;
}

std::string read_bytes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

TEST(CApiStation, TwoProcessesGiveBitIdenticalQueriesAndHarbourFields) {
  ASSERT_FALSE(kRanAsStation);
  const fs::path folder = write_sequence("station");
  // A random walk with crossfades, so the plan, the seed and the walk's draws must agree too.
  nearshore::sequence::write_loops_file(
      folder, nearshore::runtime::testing::walk_tables_for(folder, {{9, 2, 0.5, 2}, {6, 1, 0.3, 1}}, 0, 11));
  const fs::path outputs[2] = {scratch_folder() / "capi_station_a.bin", scratch_folder() / "capi_station_b.bin"};
  pid_t stations[2];
  for (int i = 0; i < 2; ++i) {
    fs::remove(outputs[i]);
    stations[i] = spawn_station(folder, outputs[i]);
    ASSERT_GT(stations[i], 0);
  }
  const std::string here = station_bytes(folder);  // this process is a third station, at the same time
  for (pid_t station : stations) {
    int status = 0;
    ASSERT_EQ(waitpid(station, &status, 0), station);
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  }
  const std::string a = read_bytes(outputs[0]), b = read_bytes(outputs[1]);
  // Nine display times of 130 samples and 1200 harbour floats each, not a message.
  ASSERT_GE(here.size(), 9 * (130 * sizeof(nearshore_surface_sample) + kColumns * kRows * sizeof(float))) << here;
  EXPECT_TRUE(a == b) << a.size() << " vs " << b.size();
  EXPECT_TRUE(a == here) << a.size() << " vs " << here.size();
  // The walk jumped (the count of transitions ends the bytes): the seed's draws were compared too.
  EXPECT_NE(here.substr(9 * (130 * sizeof(nearshore_surface_sample) + kColumns * kRows * sizeof(float))), "0");
}

}  // namespace
