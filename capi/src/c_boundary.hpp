#pragma once
// What every C entry point shares (capi/src): the sea handle, the per-thread last error, the
// status a failure carries, the guard that turns every exception into a status, and the CPU query
// behind nearshore_sea_query and nearshore_fleet_query. Private to libnearshore.so.
#include <cmath>
#include <exception>
#include <memory>
#include <new>
#include <optional>
#include <string>
#include <vector>

#include "nearshore.h"
#include "c_failure.hpp"
#include "nearshore/core/error.hpp"
#include "nearshore/core/map_projection.hpp"
#include "nearshore/runtime/library_player.hpp"
#include "nearshore/runtime/streaming_engine.hpp"
#include "nearshore/runtime/surface_sampler.hpp"

struct nearshore_sea {
  std::unique_ptr<nearshore::runtime::PlayedSea> played;  // one baked sequence, or a sea-state library
  std::optional<nearshore::MapProjection> projection;  // none for a laboratory grid
  nearshore_time_mode time_mode = NEARSHORE_TIME_FREE_RUNNING;
  // NEARSHORE_UNDERRUN from nearshore_sea_advance: for hosts of version >= 5 (their options struct
  // has time_mode); a host built before it gets NEARSHORE_OK and the counters, as it was promised.
  bool report_underruns = true;

  nearshore::runtime::StreamingEngine& engine() const { return played->engine(); }
  nearshore::runtime::SurfaceSnapshot snapshot() const { return played->snapshot(); }
  bool advance_to(double t) { return played->advance_to(t); }
};

namespace nearshore::playback {
struct SurfaceLayers;
}

namespace nearshore::capi {

/// The sea a fleet is bound to, and the fleet as the renderer's layers, rebuilt from its ships
/// as they stand (ships::FleetLayers; nearshore_fleet.cpp): what nearshore_renderer_draw adds.
const nearshore_sea* fleet_sea(const nearshore_fleet& fleet);
const nearshore::playback::SurfaceLayers& fleet_surface_layers(nearshore_fleet& fleet);

/// The message of the last failed call on this thread (nearshore_last_error).
std::string& last_error();


template <class T>
T* require(T* pointer, const char* name) {
  if (!pointer) fail(NEARSHORE_INVALID_ARGUMENT, std::string(name) + " is NULL; pass a valid pointer");
  return pointer;
}

// Runs `body`, turning every exception into a status and the thread's last error. nearshore::Error
// is the library's "bad input" (a file or a value): `error_status` says which kind it is here.
template <class Body>
nearshore_status guarded(nearshore_status error_status, Body&& body) noexcept {
  try {
    body();
    return NEARSHORE_OK;
  } catch (const Failure& failure) {
    last_error() = failure.message;
    return failure.status;
  } catch (const nearshore::Error& error) {
    last_error() = error.what();
    return error_status;
  } catch (const std::bad_alloc&) {
    last_error() = "out of memory; reduce nearshore_sea_options.ring_keyframes or close other seas";
    return NEARSHORE_INTERNAL_ERROR;
  } catch (const std::exception& error) {
    last_error() = std::string("internal error: ") + error.what();
    return NEARSHORE_INTERNAL_ERROR;
  } catch (...) {
    last_error() = "internal error: an unknown exception";
    return NEARSHORE_INTERNAL_ERROR;
  }
}

inline void fill_sample(const nearshore::runtime::SurfaceState& state, nearshore_surface_sample& sample) {
  sample.elevation_m = static_cast<float>(state.surface_elevation_m);
  sample.velocity_x_m_s = static_cast<float>(state.velocity_x_m_s);
  sample.velocity_y_m_s = static_cast<float>(state.velocity_y_m_s);
  sample.normal[0] = static_cast<float>(state.normal_x);
  sample.normal[1] = static_cast<float>(state.normal_y);
  sample.normal[2] = static_cast<float>(state.normal_z);
  sample.dry = state.dry ? 1 : 0;
}

// The surface states at the host's points (xy_m: x0, y0, x1, y1, ...), each checked finite.
inline std::vector<nearshore::runtime::SurfaceState> surface_states(const nearshore::runtime::SurfaceSnapshot& snapshot,
                                                                    const double* xy_m, std::size_t count) {
  const nearshore::runtime::SurfaceSampler sampler(snapshot);
  std::vector<nearshore::runtime::SitePoint> points(count);
  for (std::size_t i = 0; i < count; ++i) {
    if (!std::isfinite(xy_m[2 * i]) || !std::isfinite(xy_m[2 * i + 1]))
      fail(NEARSHORE_INVALID_ARGUMENT, "point " + std::to_string(i) + " of xy_m is not finite; give site metres");
    points[i] = {xy_m[2 * i], xy_m[2 * i + 1]};
  }
  std::vector<nearshore::runtime::SurfaceState> states(count);
  sampler.states(points, states);
  return states;
}

inline void query(const nearshore::runtime::SurfaceSnapshot& snapshot, const double* xy_m, std::size_t count,
                  nearshore_surface_sample* samples) {
  const std::vector<nearshore::runtime::SurfaceState> states = surface_states(snapshot, xy_m, count);
  for (std::size_t i = 0; i < count; ++i) fill_sample(states[i], samples[i]);
}

}  // namespace nearshore::capi
