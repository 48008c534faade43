#pragma once
// File checksums of the sequence manifest: XXH64 (Collet's xxHash, 64-bit variant), written from
// its public specification. It is not cryptographic; it detects truncation, flipped bits and
// swapped files at several GB/s, so verifying a whole bake costs little next to reading it.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>
#include <string>

namespace nearshore::sequence {

/// XXH64 of `bytes` with `seed` (the reference algorithm: same value as `xxhsum -H64`).
std::uint64_t xxh64(std::span<const std::byte> bytes, std::uint64_t seed = 0);

/// The manifest's spelling of a checksum: "xxh64:" followed by 16 lower-case hex digits.
std::string checksum_text(std::span<const std::byte> bytes);

/// Reads a whole file (throws nearshore::Error naming it if it cannot).
std::string read_file_bytes(const std::filesystem::path& path);

/// A growable byte buffer that is not zero-filled: reading frame after frame into the same one
/// costs one read() per file and no allocation.
struct FileBuffer {
  std::unique_ptr<std::byte[]> data;
  std::size_t size = 0, capacity = 0;
  std::span<const std::byte> bytes() const { return {data.get(), size}; }
};
/// Reads a whole file into `buffer` (throws nearshore::Error naming it if it cannot).
void read_file_into(const std::filesystem::path& path, FileBuffer& buffer);

}  // namespace nearshore::sequence
