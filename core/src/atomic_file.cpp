#include "nearshore/core/atomic_file.hpp"
#include "nearshore/core/atomic_stream.hpp"

#include <fcntl.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <streambuf>
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
// A stream buffer over a POSIX file that keeps the errno of the first failed write (std::ofstream
// only sets badbit) and can seek (flushing first), so any stream writer's failure is seen.
class DescriptorBuffer : public std::streambuf {
 public:
  explicit DescriptorBuffer(const fs::path& file)
      : descriptor_(::open(file.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644)) {
    if (descriptor_ < 0) error_ = errno;
    setp(buffer_, buffer_ + sizeof buffer_);
  }
  ~DescriptorBuffer() override {
    if (descriptor_ >= 0) ::close(descriptor_);
  }
  DescriptorBuffer(const DescriptorBuffer&) = delete;
  DescriptorBuffer& operator=(const DescriptorBuffer&) = delete;

  bool opened() const { return descriptor_ >= 0; }
  /// Writes what is buffered and closes the file; false (see error()) when anything failed.
  bool close() {
    if (descriptor_ < 0) return error_ == 0;
    flush_buffer();
    if (::close(descriptor_) != 0 && error_ == 0) error_ = errno;
    descriptor_ = -1;
    return error_ == 0;
  }
  int error() const { return error_; }  ///< errno of the first failure, 0 if none
  std::uintmax_t bytes_written() const { return written_; }

 protected:
  int_type overflow(int_type character) override {
    if (!flush_buffer()) return traits_type::eof();
    if (!traits_type::eq_int_type(character, traits_type::eof())) {
      *pptr() = traits_type::to_char_type(character);
      pbump(1);
    }
    return traits_type::not_eof(character);
  }
  std::streamsize xsputn(const char* data, std::streamsize size) override {
    // Large arrays (a solver state, a grid's leaf buffers): past the buffer, straight to the file.
    if (size < static_cast<std::streamsize>(sizeof buffer_)) return std::streambuf::xsputn(data, size);
    if (!flush_buffer() || !write_all(data, static_cast<std::size_t>(size))) return 0;
    return size;
  }
  int sync() override { return flush_buffer() ? 0 : -1; }
  pos_type seekoff(off_type offset, std::ios_base::seekdir direction, std::ios_base::openmode) override {
    if (!flush_buffer()) return pos_type(off_type(-1));
    const int whence = direction == std::ios_base::beg ? SEEK_SET : direction == std::ios_base::cur ? SEEK_CUR : SEEK_END;
    const off_t at = ::lseek(descriptor_, static_cast<off_t>(offset), whence);
    if (at < 0) {
      if (error_ == 0) error_ = errno;
      return pos_type(off_type(-1));
    }
    return pos_type(static_cast<off_type>(at));
  }
  pos_type seekpos(pos_type position, std::ios_base::openmode mode) override {
    return seekoff(off_type(position), std::ios_base::beg, mode);
  }

 private:
  bool flush_buffer() {
    const std::size_t size = static_cast<std::size_t>(pptr() - pbase());
    setp(buffer_, buffer_ + sizeof buffer_);
    return write_all(buffer_, size);
  }
  bool write_all(const char* data, std::size_t size) {
    if (error_ != 0 || descriptor_ < 0) return size == 0 && error_ == 0;
    while (size > 0) {
      const ssize_t n = ::write(descriptor_, data, size);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) {
        error_ = n == 0 ? ENOSPC : errno;  // a write that makes no progress: the device is full
        return false;
      }
      data += n, size -= static_cast<std::size_t>(n), written_ += static_cast<std::uintmax_t>(n);
    }
    return true;
  }
  int descriptor_ = -1;
  int error_ = 0;
  std::uintmax_t written_ = 0;
  char buffer_[1 << 16];
};
}  // namespace

// Whether the file system holding `folder` has (next to) no room left: what a writer's failure
// means when its library's message does not say (GDAL's "TIFFWriteDirectory failed", netCDF's "HDF
// error", OpenEXR's short write). Root may write into the reserved blocks, others may not.
static bool disk_is_full(const fs::path& folder) {
  struct statvfs disk {};
  if (::statvfs(folder.c_str(), &disk) != 0) return false;
  const double free_blocks = ::geteuid() == 0 ? static_cast<double>(disk.f_bfree) : static_cast<double>(disk.f_bavail);
  return free_blocks * static_cast<double>(disk.f_frsize) < 65536.0;
}

void write_file_atomically(const fs::path& final_path, const std::function<void(const fs::path&)>& write_to) {
  const fs::path temporary = temporary_name_for(final_path);
  const auto remove_temporary = [&] {
    std::error_code ignored;
    fs::remove(temporary, ignored);
  };
  try {
    write_to(temporary);
    fsync_file(temporary);
    std::error_code ec;
    fs::rename(temporary, final_path, ec);
    if (ec) throw Error(final_path.string(), "cannot be replaced: " + ec.message(), "check the folder's permissions");
  } catch (const Error& error) {
    // Every writer's failure on a full disk says so, whichever library's words it carries (checked
    // before the temporary file gives its space back).
    const std::string full = write_failure_reason(ENOSPC);
    const bool say_full = error.problem().find("(the disk is full)") == std::string::npos &&
                          disk_is_full(final_path.parent_path().empty() ? fs::path(".") : final_path.parent_path());
    remove_temporary();
    if (say_full) throw Error(error.subject(), error.problem() + " [" + full + "]", error.fix());
    throw;
  } catch (const std::exception& error) {
    const bool say_full = disk_is_full(final_path.parent_path().empty() ? fs::path(".") : final_path.parent_path());
    remove_temporary();
    throw Error(final_path.string(),
                std::string("writing failed: ") + error.what() + (say_full ? " [" + write_failure_reason(ENOSPC) + "]" : ""),
                "free disk space or choose another output folder; nothing was replaced");
  } catch (...) {
    remove_temporary();
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

void write_stream_atomically(const fs::path& final_path, const std::function<void(std::ostream&)>& write_to,
                             std::string_view what) {
  write_file_atomically(final_path, [&](const fs::path& temporary) {
    DescriptorBuffer buffer(temporary);
    if (!buffer.opened())
      throw Error(final_path.string(),
                  "cannot be created (" + temporary.filename().string() + "): " + std::strerror(buffer.error()),
                  "check that the folder exists and is writable");
    std::ostream out(&buffer);
    const auto failure = [&] {
      return Error(final_path.string(),
                   "writing " + std::string(what) + " failed after " + std::to_string(buffer.bytes_written()) +
                       " bytes: " + write_failure_reason(buffer.error()) + " (errno " + std::to_string(buffer.error()) + ")",
                   "free disk space or choose another output folder; nothing was replaced");
    };
    try {
      write_to(out);
      out.flush();
    } catch (...) {
      if (buffer.error() != 0) throw failure();  // the writer stumbled over the failed write: say why
      throw;
    }
    if (!buffer.close() || !out) {
      if (buffer.error() == 0)
        throw Error(final_path.string(), "writing " + std::string(what) + " failed: the writer left its stream in a failed state",
                    "report this as a bug; nothing was replaced");
      throw failure();
    }
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
