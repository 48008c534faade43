#pragma once
// What the fault tests share (faults_test.cpp, writers_test.cpp): a scratch folder per test, child
// processes (fault_runner, the `nearshore` executable), and a real full disk: a small tmpfs mounted
// in a private mount namespace of a child process, so nothing is left mounted whatever happens.
#include <sched.h>
#include <sys/mount.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace nearshore::faults {
namespace fs = std::filesystem;

/// This test's scratch folder, emptied.
inline fs::path scratch_folder() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const fs::path folder = fs::path(NEARSHORE_BINARY_DIR) / "tests" / "faults" / "scratch" /
                          (std::string(info->test_suite_name()) + "." + info->name());
  fs::remove_all(folder);
  fs::create_directories(folder);
  return folder;
}

inline std::string file_bytes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// Starts `program` with `arguments`; `fault` goes into NEARSHORE_FAULT; stderr into `log`.
inline pid_t start_program(const std::string& program, const std::vector<std::string>& arguments,
                           const std::string& fault = {}, const fs::path& log = {}) {
  const pid_t pid = fork();
  if (pid == 0) {
    if (!fault.empty()) setenv("NEARSHORE_FAULT", fault.c_str(), 1);
    if (!log.empty()) {
      if (!std::freopen(log.c_str(), "w", stderr)) _exit(126);
    }
    std::vector<char*> argv;
    argv.push_back(const_cast<char*>(program.c_str()));
    for (const std::string& argument : arguments) argv.push_back(const_cast<char*>(argument.c_str()));
    argv.push_back(nullptr);
    execv(program.c_str(), argv.data());
    _exit(127);
  }
  return pid;
}

/// fault_runner (fault_runner.cpp) with `arguments`.
inline pid_t start_runner(const std::vector<std::string>& arguments, const std::string& fault = {}, const fs::path& log = {}) {
  return start_program(FAULT_RUNNER_PATH, arguments, fault, log);
}

inline int wait_for(pid_t pid) {
  int status = 0;
  waitpid(pid, &status, 0);
  return status;
}

inline bool exited_with(int status, int code) { return WIFEXITED(status) && WEXITSTATUS(status) == code; }

/// Runs the shell `script` in a child process that has a tmpfs of `size` (mount's syntax, "2m")
/// mounted at `disk` in its own mount namespace; `environment` is exported first. Returns the
/// script's wait status, or exit status 77 with the reason in `skip_reason` where mounting is not
/// permitted (needs root or CAP_SYS_ADMIN).
inline int run_on_small_disk(const fs::path& disk, const std::string& size, const std::string& script,
                             const std::vector<std::pair<std::string, std::string>>& environment, const fs::path& skip_reason) {
  fs::create_directories(disk);
  const pid_t child = fork();
  if (child == 0) {
    const auto skip = [&](const std::string& why) {
      std::ofstream(skip_reason) << why << ": " << std::strerror(errno);
      _exit(77);
    };
    if (unshare(CLONE_NEWNS) != 0) skip("unshare(CLONE_NEWNS) for a private mount namespace failed");
    if (mount(nullptr, "/", nullptr, MS_REC | MS_PRIVATE, nullptr) != 0) skip("making the mounts private failed");
    if (mount("nearshore-faults", disk.c_str(), "tmpfs", 0, ("size=" + size).c_str()) != 0) skip("mount -t tmpfs failed");
    for (const auto& [name, value] : environment) setenv(name.c_str(), value.c_str(), 1);
    setenv("D", disk.c_str(), 1);
    execl("/bin/sh", "sh", "-c", script.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  return wait_for(child);
}

}  // namespace nearshore::faults
