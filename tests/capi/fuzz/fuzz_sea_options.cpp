// libFuzzer target for the C API's sea options (issue 44; ctest label `fuzz`, a bounded run):
// nearshore_sea_options -> sea_choice_of (capi/src/sea_options.cpp), the check every
// nearshore_sea_open and nearshore_sea_open_library runs before anything is read. The input is
// either a raw struct (its struct_size too, so short, long and foreign sizes are probed) or edits of
// a struct nearshore_sea_options_init filled: fields set to raw bits or to extreme numbers (0, -1,
// 1e308, 1e-300, 1e-12, inf, nan, 2^31, ...). Every input must end in a choice the runtime accepts
// (StreamingEngine's own preconditions: a positive finite deep-water interval, a ring of 0 or at
// least 2, a Beaufort force of 0-12 with a finite direction, a finite wait) or in a Failure with
// NEARSHORE_INVALID_ARGUMENT and a message naming a field; anything else (another status, another
// exception, a crash, a sanitizer report) is a finding.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <algorithm>
#include <string>

#include "../../../capi/src/sea_options.hpp"

namespace {

[[noreturn]] void finding(const std::string& what) {
  std::fprintf(stderr, "sea options fuzz finding: %s\n", what.c_str());
  std::abort();
}

double extreme(std::uint8_t which) {
  static const double values[] = {0.0, -1.0, 1.0, 1e308, -1e308, 1e-300, 1e-12, 1.0 / 240.0, 1.0 / 241.0,
                                  std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
                                  std::numeric_limits<double>::quiet_NaN(), 2147483648.0, -2147483649.0, 600.0,
                                  600.0000001, 720.0, -360.0, 1024.0, 1025.0, 2.0, 12.0, 13.0};
  return values[which % (sizeof values / sizeof values[0])];
}

// An enum field holding any int, as a C host may store it (a cast would be undefined in C++).
template <class Enum>
void set_int(Enum* field, int value) {
  std::memcpy(field, &value, sizeof value);
}

// Field `field` of `options` set to `value` (integers by conversion, saturated into int's range).
void set_field(nearshore_sea_options& options, std::uint8_t field, double value, std::uint64_t bits) {
  const auto as_int = [](double v) {
    if (std::isnan(v)) return 0;
    return static_cast<int>(std::fmax(std::fmin(v, 2147483647.0), -2147483648.0));
  };
  switch (field % 9) {
    case 0: set_int(&options.plan, as_int(value)); break;
    case 1: options.seed = bits; break;
    case 2: options.ring_keyframes = as_int(value); break;
    case 3: options.deep_water_interval_s = value; break;
    case 4: options.beaufort_force = as_int(value); break;
    case 5: options.wind_direction_deg = value; break;
    case 6: options.verify_checksums = as_int(value); break;
    case 7: set_int(&options.time_mode, as_int(value)); break;
    case 8: options.ready_timeout_s = value; break;
  }
}

void check_accepted(const nearshore::capi::SeaChoice& choice) {
  const nearshore::runtime::StreamingOptions& s = choice.streaming;
  if (!(s.deep_water_interval_s > 0.0) || !std::isfinite(s.deep_water_interval_s))
    finding("accepted deep_water_interval_s the engine refuses");
  if (s.ring_capacity != 0 && (s.ring_capacity < 2 || s.ring_capacity > 1024)) finding("accepted a ring outside 0, 2-1024");
  if (s.beaufort.force < 0 || s.beaufort.force > 12 || !std::isfinite(s.beaufort.wind_direction_rad))
    finding("accepted a Beaufort sea the builder refuses");
  if (!std::isfinite(choice.ready_timeout_s) || choice.ready_timeout_s < 0.0 || choice.ready_timeout_s > 600.0)
    finding("accepted a wait outside 0-600 s");
  if (choice.time_mode != NEARSHORE_TIME_FREE_RUNNING && choice.time_mode != NEARSHORE_TIME_LOCKSTEP)
    finding("accepted a time mode that is not one");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  nearshore_sea_options options;
  nearshore_sea_options_init(&options);
  if (data[0] % 4 == 0) {
    // A raw struct, struct_size included.
    std::memset(&options, 0, sizeof options);
    std::memcpy(&options, data + 1, std::min(size - 1, sizeof options));
  } else {
    // Edits: 10 bytes each, (field, kind, 8 bytes): kind even -> the bits as a double, odd -> an extreme.
    for (std::size_t at = 1; at + 10 <= size; at += 10) {
      std::uint64_t bits = 0;
      std::memcpy(&bits, data + at + 2, sizeof bits);
      double value = 0.0;
      std::memcpy(&value, &bits, sizeof value);
      if (data[at + 1] & 1u) value = extreme(data[at + 2]);
      set_field(options, data[at], value, bits);
    }
  }
  try {
    check_accepted(nearshore::capi::sea_choice_of(&options));
  } catch (const nearshore::capi::Failure& failure) {
    if (failure.status != NEARSHORE_INVALID_ARGUMENT)
      finding("a caller's value gave status " + std::to_string(int(failure.status)) + ": " + failure.message);
    if (failure.message.find("nearshore_sea_options.") == std::string::npos)
      finding("a refusal that names no field: " + failure.message);
  } catch (const std::exception& error) {
    finding(std::string("an exception that is not a status: ") + error.what());
  }
  return 0;
}
