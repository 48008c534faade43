#include "nearshore/core/folder_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <fstream>
#include <iterator>
#include <thread>
#include <utility>

#include <fmt/core.h>

#include "nearshore/core/error.hpp"

namespace nearshore {
namespace fs = std::filesystem;
namespace {

// This process's command line, as `ps` shows it, for the refused writer's message.
std::string own_command_line() {
  std::ifstream in("/proc/self/cmdline", std::ios::binary);
  std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  while (!text.empty() && text.back() == '\0') text.pop_back();
  for (char& c : text)
    if (c == '\0' || c == '\n') c = ' ';
  constexpr std::size_t kLongest = 300;  // a message, not a log
  if (text.size() > kLongest) text = text.substr(0, kLongest) + "...";
  return text;
}

std::string read_descriptor(int descriptor) {
  std::string text;
  char buffer[512];
  for (off_t offset = 0;;) {
    const ssize_t n = ::pread(descriptor, buffer, sizeof buffer, offset);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    text.append(buffer, static_cast<std::size_t>(n));
    offset += n;
    if (text.size() > 4096) break;
  }
  return text;
}

// "pid 1234\ncommand ...\npurpose ...\n" -> "PID 1234 (`...`, purpose)".
std::string describe_holder(const std::string& text) {
  std::string pid, command, purpose;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    const std::string line = text.substr(start, end - start);
    if (line.rfind("pid ", 0) == 0) pid = line.substr(4);
    else if (line.rfind("command ", 0) == 0) command = line.substr(8);
    else if (line.rfind("purpose ", 0) == 0) purpose = line.substr(8);
    start = end + 1;
  }
  if (pid.empty()) return {};
  std::string holder = "PID " + pid;
  if (!command.empty() || !purpose.empty())
    holder += " (" + (command.empty() ? purpose : purpose.empty() ? "`" + command + "`" : "`" + command + "`, " + purpose) + ")";
  return holder;
}

}  // namespace

FolderLock::FolderLock(const fs::path& folder, std::string_view purpose) : folder_(folder) {
  const fs::path file = folder / kFolderLockFile;
  descriptor_ = ::open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (descriptor_ < 0) {
    const int error = errno;
    throw Error(folder.string(), fmt::format("cannot create its lock file {}: {}", file.string(), std::strerror(error)),
                "make the folder writable, or write into another folder");
  }
  int result = 0;
  while ((result = ::flock(descriptor_, LOCK_EX | LOCK_NB)) != 0 && errno == EINTR) {
  }
  if (result != 0) {
    const int error = errno;
    if (error != EWOULDBLOCK) {
      ::close(descriptor_);
      descriptor_ = -1;
      throw Error(folder.string(), fmt::format("cannot lock {}: {}", file.string(), std::strerror(error)),
                  "write into a folder on a local disk (the folder lock needs flock)");
    }
    // The holder writes its PID right after it took the lock: give it a moment.
    std::string holder;
    for (int attempt = 0; attempt < 50 && holder.empty(); ++attempt) {
      holder = describe_holder(read_descriptor(descriptor_));
      if (holder.empty()) std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    ::close(descriptor_);
    descriptor_ = -1;
    if (holder.empty()) holder = "another process (it has not written its PID into the lock file yet)";
    throw Error(folder.string(),
                fmt::format("is in use: {} is writing into it and holds its lock {}", holder, file.string()),
                "wait until that process has finished (or stop it), or write into another folder; two writers "
                "into one folder would leave a sequence mixed from both");
  }
  const std::string text = fmt::format("pid {}\ncommand {}\npurpose {}\n", ::getpid(), own_command_line(), purpose);
  // The content is for messages only: a lock file that cannot be written still locks.
  if (::ftruncate(descriptor_, 0) == 0) {
    [[maybe_unused]] const ssize_t written = ::pwrite(descriptor_, text.data(), text.size(), 0);
  }
}

FolderLock::~FolderLock() { release(); }

FolderLock::FolderLock(FolderLock&& other) noexcept
    : folder_(std::move(other.folder_)), descriptor_(std::exchange(other.descriptor_, -1)) {}

FolderLock& FolderLock::operator=(FolderLock&& other) noexcept {
  if (this != &other) {
    release();
    folder_ = std::move(other.folder_);
    descriptor_ = std::exchange(other.descriptor_, -1);
  }
  return *this;
}

void FolderLock::release() noexcept {
  if (descriptor_ < 0) return;
  // Emptied while still held, so nobody reads a half-cleared file; closing drops the flock.
  [[maybe_unused]] const int truncated = ::ftruncate(descriptor_, 0);
  ::close(descriptor_);
  descriptor_ = -1;
}

std::string folder_lock_holder(const fs::path& folder) {
  const int descriptor = ::open((folder / kFolderLockFile).c_str(), O_RDONLY | O_CLOEXEC);
  if (descriptor < 0) return {};
  const std::string holder = describe_holder(read_descriptor(descriptor));
  ::close(descriptor);
  return holder;
}

}  // namespace nearshore
