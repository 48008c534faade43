#include "nearshore/core/hash.hpp"

#include <xxhash.h>

#include <fmt/core.h>

namespace nearshore {

std::uint64_t xxh64(std::span<const std::byte> bytes, std::uint64_t seed) {
  return XXH64(bytes.data(), bytes.size(), seed);
}

std::string checksum_text(std::span<const std::byte> bytes) { return fmt::format("xxh64:{:016x}", xxh64(bytes)); }

}  // namespace nearshore
