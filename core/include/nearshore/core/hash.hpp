#pragma once
// The one hash of the project: XXH64 (Collet's xxHash, 64-bit variant) from libxxhash. File
// checksums in manifests, the solver's state checksum and parameter fingerprint, the bake case's
// fingerprint all use it. It is not cryptographic: it detects truncation, flipped bits and swapped
// files at several GB/s.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

namespace nearshore {

/// XXH64 of `bytes` with `seed` (the same value as `xxhsum -H64`).
std::uint64_t xxh64(std::span<const std::byte> bytes, std::uint64_t seed = 0);
inline std::uint64_t xxh64(std::string_view text, std::uint64_t seed = 0) {
  return xxh64(std::as_bytes(std::span(text.data(), text.size())), seed);
}

/// The manifests' spelling of a checksum: "xxh64:" followed by 16 lower-case hex digits.
std::string checksum_text(std::span<const std::byte> bytes);

}  // namespace nearshore
