#pragma once
// The structured mutation the parsers' libFuzzer targets share (tests/bake/fuzz, tests/sequence/fuzz):
// starting from a valid document, each 3 bytes of fuzz input cut the text, replace the number at a
// place by one of `extremes`, or flip bits of one character, so the fuzzer spends its time on
// documents that are nearly right, where parsers go wrong.
#include <cctype>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

namespace nearshore::fuzzing {

inline std::string edited(std::string text, const std::uint8_t* data, std::size_t size,
                          std::span<const char* const> extremes) {
  for (std::size_t k = 0; k + 3 <= size; k += 3) {
    const std::size_t at = (static_cast<std::size_t>(data[k]) << 8 | data[k + 1]) % (text.size() + 1);
    const std::uint8_t op = data[k + 2];
    if (op == 0) {
      text.resize(at);  // a cut
    } else if (op < 16) {
      // The number at or after `at` becomes an extreme one.
      std::size_t start = at;
      while (start < text.size() && !std::isdigit(static_cast<unsigned char>(text[start]))) ++start;
      std::size_t end = start;
      while (end < text.size() && (std::isalnum(static_cast<unsigned char>(text[end])) || text[end] == '.' ||
                                   text[end] == '-' || text[end] == '+'))
        ++end;
      if (start < text.size()) text.replace(start, end - start, extremes[op % extremes.size()]);
    } else if (at < text.size()) {
      text[at] = static_cast<char>(text[at] ^ op);
    }
  }
  return text;
}

}  // namespace nearshore::fuzzing
