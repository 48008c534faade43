#include "nearshore/core/atomic_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string>

#include "nearshore/core/error.hpp"

namespace nearshore {
namespace fs = std::filesystem;

namespace {
fs::path temporary_name_for(const fs::path& final_path) {
  // Same folder, so rename() is atomic; the pid keeps two writers of one file apart.
  return final_path.parent_path() / (final_path.filename().string() + ".tmp-" + std::to_string(::getpid()));
}

void fsync_file(const fs::path& path) {
  int fd = ::open(path.c_str(), O_RDONLY);
  if (fd < 0) throw Error(path.string(), std::string("cannot be reopened to flush: ") + std::strerror(errno));
  int rc = ::fsync(fd);
  int err = errno;
  ::close(fd);
  if (rc != 0)
    throw Error(path.string(), "flushing to disk failed: " + write_failure_reason(err),
                "free disk space or choose another output folder");
}
}  // namespace

void write_file_atomically(const fs::path& final_path, const std::function<void(const fs::path&)>& write_to) {
  const fs::path temporary = temporary_name_for(final_path);
  try {
    write_to(temporary);
    fsync_file(temporary);
    std::error_code ec;
    fs::rename(temporary, final_path, ec);
    if (ec) throw Error(final_path.string(), "cannot be replaced: " + ec.message(), "check the folder's permissions");
  } catch (...) {
    std::error_code ignored;
    fs::remove(temporary, ignored);
    throw;
  }
}

void write_bytes_atomically(const fs::path& final_path, std::span<const std::byte> bytes) {
  write_file_atomically(final_path, [&](const fs::path& temporary) {
    int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd < 0)
      throw Error(final_path.string(), std::string("cannot be created: ") + std::strerror(errno),
                  "check that the folder exists and is writable");
    size_t written = 0;
    while (written < bytes.size()) {
      ssize_t n = ::write(fd, bytes.data() + written, bytes.size() - written);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) {
        int err = n == 0 ? ENOSPC : errno;  // a write that makes no progress: the device is full
        ::close(fd);
        throw Error(final_path.string(),
                    "write failed after " + std::to_string(written) + " of " + std::to_string(bytes.size()) +
                        " bytes: " + write_failure_reason(err),
                    "free disk space or choose another output folder; nothing was replaced");
      }
      written += static_cast<size_t>(n);
    }
    if (::close(fd) != 0)
      throw Error(final_path.string(), "closing failed: " + write_failure_reason(errno),
                  "free disk space or choose another output folder");
  });
}

void write_text_atomically(const fs::path& final_path, std::string_view text) {
  write_bytes_atomically(final_path, std::as_bytes(std::span(text.data(), text.size())));
}

void create_output_folder(const fs::path& folder) {
  std::error_code ec;
  fs::create_directories(folder, ec);
  if (ec || !fs::is_directory(folder))
    throw Error(folder.string(), "cannot create the output folder: " + (ec ? ec.message() : "a file has that name"),
                "choose another output folder");
}

bool is_temporary_file_name(std::string_view name) {
  // temporary_name_for(): "<final name>.tmp-<pid>"
  constexpr std::string_view marker = ".tmp-";
  const std::size_t at = name.rfind(marker);
  if (at == std::string_view::npos || at == 0) return false;
  const std::string_view pid = name.substr(at + marker.size());
  return !pid.empty() && pid.size() <= 10 && pid.find_first_not_of("0123456789") == std::string_view::npos;
}

int remove_stale_temporary_files(const fs::path& folder) {
  int removed = 0;
  std::error_code ec;
  const std::string own_suffix = ".tmp-" + std::to_string(::getpid());
  for (const auto& item : fs::directory_iterator(folder, ec)) {
    const std::string name = item.path().filename().string();
    if (!is_temporary_file_name(name) || name.ends_with(own_suffix)) continue;
    std::error_code type_error;
    if (!item.is_regular_file(type_error)) continue;
    std::error_code ignored;
    if (fs::remove(item.path(), ignored)) ++removed;
  }
  return removed;
}

std::string write_failure_reason(int error_number) {
  std::string reason = std::strerror(error_number);
  if (error_number == ENOSPC) reason += " (the disk is full)";
  if (error_number == EDQUOT) reason += " (the disk quota is full)";
  return reason;
}

}  // namespace nearshore
