#include <gtest/gtest.h>

#include <string_view>

#include "nearshore/sequence/checksum.hpp"

namespace nearshore::sequence {
namespace {

std::uint64_t hash_of(std::string_view text, std::uint64_t seed = 0) {
  return xxh64(std::as_bytes(std::span(text.data(), text.size())), seed);
}

// Published XXH64 test vectors (the reference implementation's values); the lengths cover the
// <4, 4..7, 8..31 byte tails, exactly one 32-byte stripe, several stripes, and a non-zero seed.
TEST(Checksum, MatchesReferenceXxh64Vectors) {
  EXPECT_EQ(hash_of(""), 0xef46db3751d8e999ULL);
  EXPECT_EQ(hash_of("a"), 0xd24ec4f1a98c6e5bULL);
  EXPECT_EQ(hash_of("abc"), 0x44bc2cf5ad770999ULL);
  EXPECT_EQ(hash_of("1234"), 0xd8316e61d84f6ba4ULL);
  EXPECT_EQ(hash_of("12345678"), 0xd2d02f08cf7cfd4aULL);
  EXPECT_EQ(hash_of("123456789012345"), 0xc377d78ade001a3cULL);
  EXPECT_EQ(hash_of("1234567890123456"), 0xb61c33dc6c59f270ULL);
  EXPECT_EQ(hash_of("1234567890123456789012345678901"), 0x8f367cb873a5376eULL);
  EXPECT_EQ(hash_of("12345678901234567890123456789012"), 0x40fd1aa52d98274cULL);
  EXPECT_EQ(hash_of("The quick brown fox jumps over the lazy dog"), 0x0b242d361fda71bcULL);
  EXPECT_EQ(hash_of("abc", 5381), 0x19d1c1b5c673451fULL);
  EXPECT_EQ(hash_of("12345678901234567890123456789012", 5381), 0x38ea26e7c55f8095ULL);
}

TEST(Checksum, TextFormIsPrefixedHex) {
  const std::string_view text = "abc";
  EXPECT_EQ(checksum_text(std::as_bytes(std::span(text.data(), text.size()))), "xxh64:44bc2cf5ad770999");
}

}  // namespace
}  // namespace nearshore::sequence
