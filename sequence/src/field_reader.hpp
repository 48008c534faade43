#pragma once
// Typed reads of a versioned JSON file's fields (loops.json, library.json) with messages that name
// the file, the full key ("period_loop.seams[2].from") and the fix: malformed input never escapes
// as an nlohmann exception or a crash (both parsers are fuzzed). Private to sequence/.
#include <cstdint>
#include <limits>
#include <string>
#include <string_view>
#include <utility>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "nearshore/core/error.hpp"

namespace nearshore::sequence {
namespace field_reader_detail {
inline constexpr double kInfinity = std::numeric_limits<double>::infinity();
inline constexpr long long kLargestInt = std::numeric_limits<int>::max();
}  // namespace field_reader_detail

// A JSON value in a message: numbers as written, strings quoted and cut short, else the type.
inline std::string describe(const nlohmann::json& value) {
  if (value.is_number() || value.is_boolean() || value.is_null()) return value.dump();
  if (value.is_string()) {
    std::string text = value.get_ref<const std::string&>();
    if (text.size() > 40) text = text.substr(0, 40) + "...";
    return nlohmann::json(text).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  }
  return std::string(value.is_object() ? "an object" : "an array");
}

// Typed reads of one file's fields. `path` is where the enclosing object sits
// ("period_loop.seams[2]"; empty at the top), so every message names the full key.
class FieldReader {
 public:
  FieldReader(std::string source, std::string fix) : source_(std::move(source)), fix_(std::move(fix)) {}

  [[noreturn]] void fail(const std::string& problem) const { throw Error(source_, problem, fix_); }

  /// The root object of a versioned file: valid JSON, an object, "format": `format` (else it is
  /// not `what`, e.g. "a loops table"), "version" an integer no newer than `version` (a newer one
  /// is refused as such, with `newer_fix`, before any key it may have renamed) and equal to it.
  nlohmann::json versioned_root(std::string_view text, std::string_view format, std::string_view what, int version,
                                const std::string& newer_fix, const std::string& write_fix) const {
    nlohmann::json root;
    try {
      root = nlohmann::json::parse(text);
    } catch (const nlohmann::json::parse_error& e) {
      fail(fmt::format("is not valid JSON (byte {} of {}: truncated or corrupt)", e.byte, text.size()));
    }
    if (!root.is_object()) fail(fmt::format("is {}, not a JSON object", describe(root)));
    const nlohmann::json& found_format = member(root, "", "format");
    if (!found_format.is_string() || found_format.get_ref<const std::string&>() != format)
      throw Error(source_, fmt::format("is not {} (\"format\" is {}, not \"{}\")", what, describe(found_format), format),
                  write_fix);
    const nlohmann::json& found_version = member(root, "", "version");
    if (!found_version.is_number_integer()) wrong_type(found_version, "", "version", "an integer");
    if (found_version > version)
      throw Error(source_,
                  fmt::format("has \"{}\" version {}, newer than version {} that this nearshore reads", format,
                              found_version.dump(), version),
                  newer_fix);
    if (found_version != version)
      fail(fmt::format("has \"{}\" version {}, which no nearshore writes (this one reads version {})", format,
                       found_version.dump(), version));
    return root;
  }
  const std::string& fix() const { return fix_; }

  static std::string name(const std::string& path, std::string_view key) {
    return path.empty() ? std::string(key) : fmt::format("{}.{}", path, key);
  }

  [[noreturn]] void wrong_type(const nlohmann::json& value, const std::string& path, std::string_view key,
                               const char* wanted) const {
    fail(fmt::format("\"{}\" is {}, not {}", name(path, key), describe(value), wanted));
  }

  const nlohmann::json& member(const nlohmann::json& object, const std::string& path, const char* key) const {
    const auto it = object.find(key);
    if (it == object.end()) fail(fmt::format("has no \"{}\"", name(path, key)));
    return *it;
  }

  const nlohmann::json& object(const nlohmann::json& parent, const std::string& path, const char* key) const {
    const nlohmann::json& value = member(parent, path, key);
    if (!value.is_object()) wrong_type(value, path, key, "an object");
    return value;
  }

  const nlohmann::json& array(const nlohmann::json& parent, const std::string& path, const char* key) const {
    const nlohmann::json& value = member(parent, path, key);
    if (!value.is_array()) wrong_type(value, path, key, "an array");
    return value;
  }

  std::string text(const nlohmann::json& parent, const std::string& path, const char* key) const {
    const nlohmann::json& value = member(parent, path, key);
    if (!value.is_string()) wrong_type(value, path, key, "a string");
    return value.get<std::string>();
  }

  bool boolean(const nlohmann::json& parent, const std::string& path, const char* key) const {
    const nlohmann::json& value = member(parent, path, key);
    if (!value.is_boolean()) wrong_type(value, path, key, "true or false");
    return value.get<bool>();
  }

  // A number; null is +infinity (JSON has none; see the header).
  double number_value(const nlohmann::json& value, const std::string& path, std::string_view key) const {
    if (value.is_null()) return field_reader_detail::kInfinity;
    if (!value.is_number()) wrong_type(value, path, key, "a number");
    return value.get<double>();
  }
  double number(const nlohmann::json& parent, const std::string& path, const char* key) const {
    return number_value(member(parent, path, key), path, key);
  }

  // An integer in [low, high]; `meaning` says what the range is, for the message.
  int integer_value(const nlohmann::json& value, const std::string& path, std::string_view key, long long low,
                    long long high, std::string_view meaning = {}) const {
    if (!value.is_number_integer()) wrong_type(value, path, key, "an integer");
    const bool inside = value.is_number_unsigned()
                            ? high >= 0 && value.get<std::uint64_t>() <= static_cast<std::uint64_t>(high) &&
                                  static_cast<long long>(value.get<std::uint64_t>()) >= low
                            : value.get<std::int64_t>() >= low && value.get<std::int64_t>() <= high;
    if (!inside)
      fail(fmt::format("\"{}\" is {}, outside {}..{}{}{}", name(path, key), value.dump(), low, high,
                       meaning.empty() ? "" : " ", meaning));
    return static_cast<int>(value.get<std::int64_t>());
  }
  int integer(const nlohmann::json& parent, const std::string& path, const char* key, long long low = 0,
              long long high = field_reader_detail::kLargestInt, std::string_view meaning = {}) const {
    return integer_value(member(parent, path, key), path, key, low, high, meaning);
  }

  // A frame index of the bake (0 .. frame_count - 1; -1 too where "none" is allowed).
  int frame_value(const nlohmann::json& value, const std::string& path, std::string_view key, int frame_count,
                  bool none_allowed = false) const {
    return integer_value(value, path, key, none_allowed ? -1 : 0, frame_count - 1,
                         none_allowed ? "(a frame of the bake, or -1 for none)" : "(the frames of the bake)");
  }
  int frame(const nlohmann::json& parent, const std::string& path, const char* key, int frame_count,
            bool none_allowed = false) const {
    return frame_value(member(parent, path, key), path, key, frame_count, none_allowed);
  }

  // The crossfade of a jump from -> to blends frames from - c + 1 .. from with to - c .. to - 1
  // (loop_playback.hpp), which must all exist: 0 <= c <= min(to, from + 1).
  int crossfade_value(const nlohmann::json& value, const std::string& path, std::string_view key, int from,
                      int to) const {
    return integer_value(value, path, key, 0, std::min(to, from + 1),
                         "(the blends of a crossfade must be frames of the bake)");
  }

 private:
  std::string source_, fix_;
};

}  // namespace nearshore::sequence
