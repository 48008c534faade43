// The sea options of the C API (nearshore_sea_options) checked field by field and turned into the
// runtime's StreamingOptions: every number has a range with its reason (issue 44), a caller's
// value outside it is NEARSHORE_INVALID_ARGUMENT naming the field. Apart from nearshore_c.cpp so
// that the fuzz target (tests/capi/fuzz) builds it with nothing else of the library.
#include "sea_options.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <string>

#include <fmt/format.h>

#include "nearshore/ocean/sea_state_beaufort.hpp"

namespace nearshore::capi {

namespace {
// A C enum field as the int a host stored in it: a value outside the enumerators is the host's
// mistake to refuse, and loading it as the C++ enum type would be undefined behaviour (the fuzz
// target's first finding).
template <class Enum>
int enum_value(const Enum& field) {
  static_assert(sizeof(Enum) == sizeof(int));
  int value = 0;
  std::memcpy(&value, &field, sizeof value);
  return value;
}

nearshore::runtime::PlanKind plan_kind(int plan) {
  switch (plan) {
    case NEARSHORE_PLAN_AUTO:
    case NEARSHORE_PLAN_OPTIMAL_LOOP: return nearshore::runtime::PlanKind::kOptimalLoop;
    case NEARSHORE_PLAN_EXACT_PERIOD: return nearshore::runtime::PlanKind::kExactPeriod;
    case NEARSHORE_PLAN_RANDOM_WALK: return nearshore::runtime::PlanKind::kRandomWalk;
    case NEARSHORE_PLAN_FRAME_ORDER: return nearshore::runtime::PlanKind::kFrameOrder;
  }
  fail(NEARSHORE_INVALID_ARGUMENT, "nearshore_sea_options.plan = " + std::to_string(plan) +
                                       " is not a nearshore_plan; use NEARSHORE_PLAN_AUTO .. NEARSHORE_PLAN_FRAME_ORDER");
}

}  // namespace

double checked(double value, const char* field, double low, double high, const char* reason) {
  if (!std::isfinite(value) || value < low || value > high)
    fail(NEARSHORE_INVALID_ARGUMENT, fmt::format("{} = {:.6g} is outside {:.6g} - {:.6g}: {}", field, value, low, high, reason));
  return value;
}

nearshore::runtime::BeaufortSea beaufort_sea(int force, double wind_from_deg) {
  if (force < 0 || force > 12)
    fail(NEARSHORE_INVALID_ARGUMENT, "beaufort_force = " + std::to_string(force) + " is outside 0-12; give a force of the Beaufort scale");
  checked(wind_from_deg, "wind_direction_deg", -360.0, 720.0,
          "a compass direction in degrees (one turn either side of 0-360, so a host's unwrapped angle is taken)");
  nearshore::runtime::BeaufortSea sea;
  sea.force = force;
  sea.wind_direction_rad = nearshore::ocean::travel_direction_rad(wind_from_deg);
  return sea;
}

SeaChoice sea_choice_of(const nearshore_sea_options* options) {
  nearshore_sea_options chosen;
  nearshore_sea_options_init(&chosen);
  SeaChoice choice;
  if (options) {
    if (options->struct_size < sizeof(uint32_t) || options->struct_size > sizeof(nearshore_sea_options))
      fail(NEARSHORE_INVALID_ARGUMENT, "nearshore_sea_options.struct_size = " + std::to_string(options->struct_size) +
                                           "; call nearshore_sea_options_init first");
    // A struct of version 4 ends at verify_checksums (time_mode would fall in its padding): the
    // fields of version 5 are read only from a struct that holds them whole.
    constexpr std::size_t kVersion5Size = offsetof(nearshore_sea_options, ready_timeout_s) + sizeof(double);
    const std::size_t version4_size = offsetof(nearshore_sea_options, time_mode);
    std::memcpy(&chosen, options, options->struct_size >= kVersion5Size ? options->struct_size
                                                                          : std::min<std::size_t>(options->struct_size, version4_size));
    if (options->struct_size < kVersion5Size) choice.report_underruns = false;
  }
  nearshore::runtime::StreamingOptions& streaming = choice.streaming;
  streaming.plan = plan_kind(enum_value(chosen.plan));
  if (chosen.seed != 0) streaming.seed = chosen.seed;
  if (chosen.ring_keyframes != 0)
    checked(chosen.ring_keyframes, "nearshore_sea_options.ring_keyframes", 2, 1024,
            "the ring holds the keyframe shown and the next at least, and 1024 keyframes of even a 256 x 256 bake "
            "are 1 GiB; 0 chooses about 1 s of play within 512 MiB");
  streaming.ring_capacity = chosen.ring_keyframes;
  if (chosen.deep_water_interval_s != 0.0)
    streaming.deep_water_interval_s =
        checked(chosen.deep_water_interval_s, "nearshore_sea_options.deep_water_interval_s", 1.0 / 240.0, 1.0,
                "one deep-water keyframe per displayed frame of a 240 Hz screen at most (each costs an FFT set), and at "
                "least one a second for the interpolation between keyframes to follow waves; 0 chooses 1/30 s");
  if (chosen.beaufort_force != -1)
    checked(chosen.beaufort_force, "nearshore_sea_options.beaufort_force", 0, 12,
            "a force of the Beaufort scale; -1 chooses the default (force 3)");
  // Checked whether or not a force is given: a direction that is not one is a caller's mistake.
  checked(chosen.wind_direction_deg, "nearshore_sea_options.wind_direction_deg", -360.0, 720.0,
          "a compass direction in degrees (one turn either side of 0-360, so a host's unwrapped angle is taken)");
  if (chosen.beaufort_force >= 0) streaming.beaufort = beaufort_sea(chosen.beaufort_force, chosen.wind_direction_deg);
  streaming.verify = chosen.verify_checksums ? nearshore::sequence::Verify::kYes : nearshore::sequence::Verify::kNo;
  const int time_mode = enum_value(chosen.time_mode);
  if (time_mode != NEARSHORE_TIME_FREE_RUNNING && time_mode != NEARSHORE_TIME_LOCKSTEP)
    fail(NEARSHORE_INVALID_ARGUMENT, "nearshore_sea_options.time_mode = " + std::to_string(time_mode) +
                                         " is not a nearshore_time_mode; use NEARSHORE_TIME_FREE_RUNNING or "
                                         "NEARSHORE_TIME_LOCKSTEP");
  choice.time_mode = static_cast<nearshore_time_mode>(time_mode);
  streaming.lockstep = time_mode == NEARSHORE_TIME_LOCKSTEP;
  choice.ready_timeout_s = checked(chosen.ready_timeout_s, "nearshore_sea_options.ready_timeout_s", 0.0, 600.0,
                                   "seconds the open waits for the first frame; past 10 minutes a disk is not "
                                   "answering and waiting longer hides it; 0 does not wait");
  return choice;
}

}  // namespace nearshore::capi

extern "C" {

void nearshore_sea_options_init(nearshore_sea_options* options) {
  if (!options) return;
  *options = {};
  options->struct_size = sizeof(nearshore_sea_options);
  options->plan = NEARSHORE_PLAN_AUTO;
  options->beaufort_force = -1;
  options->wind_direction_deg = 225.0;  // a south-westerly, the prevailing wind of the mid-latitudes
  options->time_mode = NEARSHORE_TIME_FREE_RUNNING;
  options->ready_timeout_s = nearshore::capi::kDefaultReadyTimeout_s;
}

}  // extern "C"
