#pragma once
// nearshore_sea_options -> runtime::StreamingOptions, every field checked (sea_options.cpp).
// Private to libnearshore.so and its fuzz target.
#include "nearshore.h"
#include "c_failure.hpp"
#include "nearshore/runtime/streaming_engine.hpp"

namespace nearshore::capi {

/// The open waits this long by default for the first frame: two keyframes of a 1024 x 1024 bake
/// decode in about 20 ms and a deep-water keyframe in 1-30 ms, so 10 s only runs out on a disk
/// that does not answer.
inline constexpr double kDefaultReadyTimeout_s = 10.0;

/// What nearshore_sea_options asks for, checked.
struct SeaChoice {
  nearshore::runtime::StreamingOptions streaming;
  nearshore_time_mode time_mode = NEARSHORE_TIME_FREE_RUNNING;
  double ready_timeout_s = kDefaultReadyTimeout_s;
  /// NEARSHORE_UNDERRUN from nearshore_sea_advance: hosts of version >= 5 (a struct with time_mode).
  bool report_underruns = true;
};

/// `options` (NULL: the defaults) checked field by field; throws Failure (NEARSHORE_INVALID_ARGUMENT,
/// naming the field, its range and why) for a value outside its range. What it returns, the
/// runtime never refuses (the fuzz target holds this: a caller's mistake is never another status).
SeaChoice sea_choice_of(const nearshore_sea_options* options);

/// `value` inside [low, high] and finite, or Failure naming `field`, the range and `reason`.
double checked(double value, const char* field, double low, double high, const char* reason);

/// The Beaufort sea of a force (0-12) and a compass direction the wind blows from (degrees).
nearshore::runtime::BeaufortSea beaufort_sea(int force, double wind_from_deg);

}  // namespace nearshore::capi
