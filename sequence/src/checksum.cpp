#include "nearshore/sequence/checksum.hpp"

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <fstream>

#include <fmt/core.h>

#include "nearshore/core/error.hpp"

namespace nearshore::sequence {

namespace {

// A folder opens for reading on Linux and reports a size, so without this check reading one ends
// in a bogus allocation ("std::bad_alloc") or a failed read that names nothing.
void require_not_a_folder(const std::filesystem::path& path, bool is_folder) {
  if (is_folder)
    throw Error(path.string(), "is a folder, not a file",
                "give the path of the file, or remove the folder that stands in its place");
}

}  // namespace

std::string read_file_bytes(const std::filesystem::path& path) {
  std::error_code ec;
  require_not_a_folder(path, std::filesystem::is_directory(path, ec));
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in)
    throw Error(path.string(), std::string("cannot be opened for reading: ") + std::strerror(errno),
                "check that it exists and is readable");
  const std::streamoff size = in.tellg();
  if (size < 0)
    throw Error(path.string(), "has no size that can be read (not a regular file?)", "give the path of a file");
  std::string bytes(static_cast<std::size_t>(size), '\0');
  in.seekg(0);
  if (size > 0 && !in.read(bytes.data(), size))
    throw Error(path.string(), fmt::format("reading {} bytes failed", size), "check the disk and the file");
  return bytes;
}

void read_file_into(const std::filesystem::path& path, FileBuffer& buffer) {
  const int fd = ::open(path.c_str(), O_RDONLY);
  if (fd < 0)
    throw Error(path.string(), std::string("cannot be opened for reading: ") + std::strerror(errno),
                "check that it exists and is readable");
  struct stat status {};
  if (::fstat(fd, &status) != 0) {
    const int error = errno;
    ::close(fd);
    throw Error(path.string(), std::string("cannot be inspected: ") + std::strerror(error), "check the disk");
  }
  if (S_ISDIR(status.st_mode)) {
    ::close(fd);
    require_not_a_folder(path, true);
  }
  const std::size_t size = static_cast<std::size_t>(status.st_size);
  if (size > buffer.capacity) {
    buffer.data = std::make_unique_for_overwrite<std::byte[]>(size);
    buffer.capacity = size;
  }
  std::size_t done = 0;
  while (done < size) {
    const ssize_t n = ::read(fd, buffer.data.get() + done, size - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;  // shrunk while reading: keep what is there, the checks downstream see it
    done += static_cast<std::size_t>(n);
  }
  ::close(fd);
  buffer.size = done;
}

}  // namespace nearshore::sequence
