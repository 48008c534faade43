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
    throw Error(path.string(), std::string("flushing to disk failed: ") + std::strerror(err),
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
        int err = errno;
        ::close(fd);
        throw Error(final_path.string(),
                    "write failed after " + std::to_string(written) + " of " + std::to_string(bytes.size()) +
                        " bytes: " + std::strerror(err),
                    "free disk space or choose another output folder; nothing was replaced");
      }
      written += static_cast<size_t>(n);
    }
    if (::close(fd) != 0)
      throw Error(final_path.string(), std::string("closing failed: ") + std::strerror(errno),
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
                "choose another -o folder");
}

}  // namespace nearshore
