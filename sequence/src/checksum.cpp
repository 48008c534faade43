#include "nearshore/sequence/checksum.hpp"

#include <bit>
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

// XXH64 constants and round functions (xxHash specification, "XXH64 algorithm description").
constexpr std::uint64_t kPrime1 = 0x9E3779B185EBCA87ULL;
constexpr std::uint64_t kPrime2 = 0xC2B2AE3D27D4EB4FULL;
constexpr std::uint64_t kPrime3 = 0x165667B19E3779F9ULL;
constexpr std::uint64_t kPrime4 = 0x85EBCA77C2B2AE63ULL;
constexpr std::uint64_t kPrime5 = 0x27D4EB2F165667C5ULL;

std::uint64_t load64(const std::byte* p) {
  std::uint64_t value;
  std::memcpy(&value, p, sizeof value);
  if constexpr (std::endian::native == std::endian::big) value = __builtin_bswap64(value);
  return value;
}
std::uint32_t load32(const std::byte* p) {
  std::uint32_t value;
  std::memcpy(&value, p, sizeof value);
  if constexpr (std::endian::native == std::endian::big) value = __builtin_bswap32(value);
  return value;
}
std::uint64_t round(std::uint64_t accumulator, std::uint64_t lane) {
  accumulator += lane * kPrime2;
  accumulator = std::rotl(accumulator, 31);
  return accumulator * kPrime1;
}
std::uint64_t merge_round(std::uint64_t accumulator, std::uint64_t lane) {
  accumulator ^= round(0, lane);
  return accumulator * kPrime1 + kPrime4;
}

}  // namespace

std::uint64_t xxh64(std::span<const std::byte> bytes, std::uint64_t seed) {
  const std::byte* p = bytes.data();
  const std::byte* const end = p + bytes.size();
  std::uint64_t hash;
  if (bytes.size() >= 32) {
    // Four independent lanes over 32-byte stripes.
    std::uint64_t v1 = seed + kPrime1 + kPrime2, v2 = seed + kPrime2, v3 = seed, v4 = seed - kPrime1;
    const std::byte* const last_stripe = end - 32;
    do {
      v1 = round(v1, load64(p));
      v2 = round(v2, load64(p + 8));
      v3 = round(v3, load64(p + 16));
      v4 = round(v4, load64(p + 24));
      p += 32;
    } while (p <= last_stripe);
    hash = std::rotl(v1, 1) + std::rotl(v2, 7) + std::rotl(v3, 12) + std::rotl(v4, 18);
    hash = merge_round(hash, v1);
    hash = merge_round(hash, v2);
    hash = merge_round(hash, v3);
    hash = merge_round(hash, v4);
  } else {
    hash = seed + kPrime5;
  }
  hash += static_cast<std::uint64_t>(bytes.size());
  for (; p + 8 <= end; p += 8) hash = std::rotl(hash ^ round(0, load64(p)), 27) * kPrime1 + kPrime4;
  if (p + 4 <= end) {
    hash = std::rotl(hash ^ (static_cast<std::uint64_t>(load32(p)) * kPrime1), 23) * kPrime2 + kPrime3;
    p += 4;
  }
  for (; p < end; ++p) hash = std::rotl(hash ^ (std::to_integer<std::uint64_t>(*p) * kPrime5), 11) * kPrime1;
  // Avalanche.
  hash ^= hash >> 33;
  hash *= kPrime2;
  hash ^= hash >> 29;
  hash *= kPrime3;
  hash ^= hash >> 32;
  return hash;
}

std::string checksum_text(std::span<const std::byte> bytes) { return fmt::format("xxh64:{:016x}", xxh64(bytes)); }

std::string read_file_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in)
    throw Error(path.string(), std::string("cannot be opened for reading: ") + std::strerror(errno),
                "check that it exists and is readable");
  const std::streamoff size = in.tellg();
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
