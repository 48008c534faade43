// The C API (include/nearshore.h) over the C++ runtime: runtime::StreamingEngine (streaming, deep
// water), runtime::SurfaceSampler (CPU queries) and playback::WaterRenderer (drawing in the host's
// context). Every entry point catches everything: no exception crosses the C boundary; the message
// goes to a per-thread last-error string and the call returns a status.
#include "nearshore.h"
#include "c_boundary.hpp"
#include "sea_options.hpp"

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <cmath>
#include <cstring>
#include <exception>
#include <filesystem>
#include <limits>
#include <memory>
#include <new>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "nearshore/core/error.hpp"
#include "nearshore/core/map_projection.hpp"
#include "nearshore/ocean/sea_state_beaufort.hpp"
#include "nearshore/ocean/whitecap_coverage.hpp"
#include "nearshore/playback/gl_loader.hpp"
#include "nearshore/playback/lighting.hpp"
#include "nearshore/playback/sun_position.hpp"
#include "nearshore/playback/water_renderer.hpp"
#include "nearshore/runtime/library_player.hpp"
#include "nearshore/runtime/streaming_engine.hpp"
#include "nearshore/runtime/surface_sampler.hpp"

struct nearshore_renderer {
  nearshore_sea* sea = nullptr;
  std::unique_ptr<nearshore::playback::WaterRenderer> renderer;
  int last_width_px = 0, last_height_px = 0;
  // Set by nearshore_renderer_set_lighting; the sun is the camera's unless sun_from_time.
  nearshore::playback::Lighting lighting;
  bool sun_from_time = false;
  nearshore_fleet* fleet = nullptr;  // drawn with the sea (nearshore_renderer_set_fleet)
  // The deep water's foam onset J_b for Monahan's whitecap coverage at the lighting's wind,
  // measured on the deep keyframe drawn when the sea or the wind changes (as nearshore play does).
  nearshore::ocean::WhitecapFoamOnset whitecaps;
  double jacobian_foam_onset = nearshore::playback::Lighting{}.jacobian_foam_onset;
};

namespace nearshore::capi {

std::string& last_error() {
  thread_local std::string message;
  return message;
}

}  // namespace nearshore::capi

namespace {
namespace fs = std::filesystem;
using nearshore::Error;
using namespace nearshore::capi;
using nearshore::ocean::travel_direction_rad;  // compass "from" bearing -> travel direction

template <std::size_t N>
void copy_text(char (&out)[N], const std::string& text) {
  const std::size_t length = std::min(text.size(), N - 1);
  std::memcpy(out, text.data(), length);
  out[length] = '\0';
}

}  // namespace

extern "C" {

const char* nearshore_last_error(void) { return nearshore::capi::last_error().c_str(); }

const char* nearshore_status_name(nearshore_status status) {
  switch (status) {
    case NEARSHORE_OK: return "NEARSHORE_OK";
    case NEARSHORE_INVALID_ARGUMENT: return "NEARSHORE_INVALID_ARGUMENT";
    case NEARSHORE_IO_ERROR: return "NEARSHORE_IO_ERROR";
    case NEARSHORE_FORMAT_ERROR: return "NEARSHORE_FORMAT_ERROR";
    case NEARSHORE_GL_ERROR: return "NEARSHORE_GL_ERROR";
    case NEARSHORE_INTERNAL_ERROR: return "NEARSHORE_INTERNAL_ERROR";
    case NEARSHORE_TIMEOUT: return "NEARSHORE_TIMEOUT";
    case NEARSHORE_UNDERRUN: return "NEARSHORE_UNDERRUN";
  }
  return "NEARSHORE_UNKNOWN_STATUS";
}

int nearshore_api_version(void) { return NEARSHORE_API_VERSION; }

}  // extern "C"

namespace {

void set_projection(nearshore_sea& sea, const fs::path& folder);

// Waits for display time `time_s` on every state shown; NEARSHORE_TIMEOUT naming what was asked.
void wait_until_ready(nearshore_sea& sea, double time_s, double timeout_s, const char* asked_by) {
  const auto timeout = std::chrono::milliseconds(static_cast<long long>(std::ceil(timeout_s * 1000.0)));
  if (sea.played->wait_until_ready(time_s, timeout)) return;
  const nearshore::runtime::StreamingStats stats = sea.engine().stats();
  fail(NEARSHORE_TIMEOUT, fmt::format("the keyframes of display time {:.6g} s were not decoded within {} = {:.6g} s "
                                      "({} harbour keyframes decoded, {} deep-water keyframes synthesised so far{}{}); "
                                      "wait longer, or use NEARSHORE_TIME_LOCKSTEP, which makes them when asked",
                                      time_s, asked_by, timeout_s, stats.keyframes_decoded, stats.deep_keyframes_synthesised,
                                      stats.last_message.empty() ? "" : "; ", stats.last_message));
}

// Opens a sea with `choice` and waits for its first frame as asked.
void open_sea(nearshore_sea** sea, const fs::path& folder, const nearshore::sequence::SeaConditions& conditions,
              const SeaChoice& choice) {
  auto opened = std::make_unique<nearshore_sea>();
  opened->played = std::make_unique<nearshore::runtime::PlayedSea>(folder, conditions, choice.streaming);
  opened->time_mode = choice.time_mode;
  opened->report_underruns = choice.report_underruns;
  set_projection(*opened, folder);
  if (choice.ready_timeout_s > 0.0)
    wait_until_ready(*opened, 0.0, choice.ready_timeout_s, "nearshore_sea_options.ready_timeout_s");
  *sea = opened.release();
}

// A display time (runtime::is_display_time: finite, 0 - 1e9 s).
void checked_time(double time_s, const char* field) {
  if (!nearshore::runtime::is_display_time(time_s))
    fail(NEARSHORE_INVALID_ARGUMENT, fmt::format("{} = {:.6g} is outside 0 - {:g} s: a display time of the sea's timeline "
                                                 "(time 0 is the first step of its plan)",
                                                 field, time_s, nearshore::runtime::kLatestDisplayTime_s));
}

// Points of one query call: at most 2^26 (64 Mi points, 1.5 GiB of input and output), so a
// wrapped size_t is refused instead of allocating.
void checked_count(std::size_t count) {
  if (count > (std::size_t{1} << 26))
    fail(NEARSHORE_INVALID_ARGUMENT, fmt::format("count = {} points is above 2^26 in one call: a negative number passed "
                                                 "as size_t? Query in batches", count));
}

// "KEY=VALUE,..." (NULL: none) as the library's conditions; a bad item is an invalid argument.
nearshore::sequence::SeaConditions conditions_of(const char* text) {
  try {
    return nearshore::sequence::parse_sea_conditions(text ? text : "", "conditions");
  } catch (const Error& error) {
    fail(NEARSHORE_INVALID_ARGUMENT, error.what());
  }
}

// The folder a sea opens, checked before anything is read: a missing one is an I/O error.
fs::path existing_folder(const char* folder_text, const char* parameter, const char* needed_file, const char* made_by) {
  const fs::path folder = require(folder_text, parameter);
  if (!fs::is_directory(folder))
    fail(NEARSHORE_IO_ERROR, folder.string() + ": no such folder; give the output folder of " + made_by);
  if (!fs::is_regular_file(folder / needed_file))
    fail(NEARSHORE_IO_ERROR, (folder / needed_file).string() + ": missing (an unfinished run of " + made_by +
                                 "?); finish or resume it first");
  return folder;
}

void set_projection(nearshore_sea& sea, const fs::path& folder) {
  const nlohmann::json& projection = sea.engine().manifest().geometry.projection;
  if (projection.is_object() && !projection.empty())
    sea.projection = nearshore::MapProjection::from_json(projection, (folder / "manifest.json").string());
}

}  // namespace

extern "C" {

nearshore_status nearshore_sea_open(const char* sequence_folder, const nearshore_sea_options* options,
                                    nearshore_sea** sea) {
  return guarded(NEARSHORE_FORMAT_ERROR, [&] {
    require(sea, "sea");
    *sea = nullptr;
    const fs::path folder = existing_folder(sequence_folder, "sequence_folder", "manifest.json", "`nearshore bake`");
    open_sea(sea, folder, nearshore::sequence::SeaConditions{}, sea_choice_of(options));
  });
}

nearshore_status nearshore_sea_open_library(const char* library_folder, const char* conditions,
                                            const nearshore_sea_options* options, nearshore_sea** sea) {
  return guarded(NEARSHORE_FORMAT_ERROR, [&] {
    require(sea, "sea");
    *sea = nullptr;
    const fs::path folder = existing_folder(library_folder, "library_folder", "library.json", "`nearshore library`");
    const nearshore::sequence::SeaConditions requested = conditions_of(conditions);
    open_sea(sea, folder, requested, sea_choice_of(options));
  });
}

nearshore_status nearshore_sea_request_conditions(nearshore_sea* sea, const char* conditions, double crossfade_s,
                                                  char state_id[64]) {
  return guarded(NEARSHORE_INTERNAL_ERROR, [&] {
    require(sea, "sea");
    nearshore::runtime::LibraryPlayer* library = sea->played->library();
    if (!library)
      fail(NEARSHORE_INVALID_ARGUMENT, "this sea is one sequence, not a sea-state library; open it with "
                                       "nearshore_sea_open_library");
    const nearshore::sequence::SeaConditions requested = conditions_of(conditions);
    if (!(crossfade_s >= 0.0 && crossfade_s <= 3600.0))
      fail(NEARSHORE_INVALID_ARGUMENT, "crossfade_s = " + std::to_string(crossfade_s) + " is outside 0-3600 s");
    const std::string& id = library->request(requested, crossfade_s);
    if (state_id) {
      const std::size_t length = std::min<std::size_t>(id.size(), 63);
      std::memcpy(state_id, id.data(), length);
      state_id[length] = '\0';
    }
  });
}

void nearshore_sea_close(nearshore_sea* sea) { delete sea; }

nearshore_status nearshore_sea_advance(nearshore_sea* sea, double time_s) {
  // A nearshore::Error here is a frame the slow path could not make (lockstep): bad input.
  bool planned = true;
  const nearshore_status status = guarded(NEARSHORE_IO_ERROR, [&] {
    require(sea, "sea");
    checked_time(time_s, "time_s");
    planned = sea->advance_to(time_s);
  });
  if (status != NEARSHORE_OK || planned || !sea->report_underruns) return status;
  const nearshore::runtime::StreamingStats stats = sea->engine().stats();
  nearshore::capi::last_error() =
      fmt::format("display time {:.6g} s shows older keyframes: the background decoder has not made the planned ones "
                  "yet ({} underruns so far: {} harbour, {} deep water); keep advancing, wait with "
                  "nearshore_sea_wait_until_ready, or open the sea with NEARSHORE_TIME_LOCKSTEP",
                  time_s, stats.underruns, stats.harbour_underruns, stats.deep_underruns);
  return NEARSHORE_UNDERRUN;
}

nearshore_status nearshore_sea_wait_until_ready(nearshore_sea* sea, double time_s, double timeout_s) {
  return guarded(NEARSHORE_IO_ERROR, [&] {
    require(sea, "sea");
    checked_time(time_s, "time_s");
    checked(timeout_s, "timeout_s", 0.0, 600.0, "seconds to wait; past 10 minutes a disk is not answering");
    wait_until_ready(*sea, time_s, timeout_s, "timeout_s");
  });
}

nearshore_status nearshore_sea_set_wind(nearshore_sea* sea, int beaufort_force, double wind_direction_deg) {
  return guarded(NEARSHORE_INVALID_ARGUMENT, [&] {
    require(sea, "sea");
    sea->engine().set_beaufort(beaufort_sea(beaufort_force, wind_direction_deg));
  });
}

nearshore_status nearshore_site_info_get(const nearshore_sea* sea, nearshore_site_info* info) {
  return guarded(NEARSHORE_INTERNAL_ERROR, [&] {
    require(sea, "sea");
    require(info, "info");
    if (info->struct_size != sizeof(nearshore_site_info))
      fail(NEARSHORE_INVALID_ARGUMENT, "nearshore_site_info.struct_size must be sizeof(nearshore_site_info)");
    const nearshore::GridGeometry& geometry = sea->engine().manifest().geometry;
    info->columns = geometry.columns;
    info->rows = geometry.rows;
    info->cell_size_x_m = geometry.spacing_x_m();
    info->cell_size_y_m = geometry.spacing_y_m();
    info->width_m = geometry.width_m();
    info->height_m = geometry.height_m();
    info->origin_x_m = geometry.origin_x_m;
    info->origin_y_m = geometry.origin_y_m;
    info->origin_latitude_deg = info->origin_longitude_deg = std::numeric_limits<double>::quiet_NaN();
    if (sea->projection) {
      const nearshore::LonLat corner = sea->projection->reverse({geometry.origin_x_m, geometry.origin_y_m});
      info->origin_latitude_deg = corner.latitude_deg;
      info->origin_longitude_deg = corner.longitude_deg;
    }
    info->frame_interval_s = sea->engine().frame_interval_s();
    info->frame_count = sea->engine().manifest().frame_count;
  });
}

nearshore_status nearshore_site_from_lat_lon(const nearshore_sea* sea, double latitude_deg, double longitude_deg,
                                             double* x_m, double* y_m) {
  return guarded(NEARSHORE_INVALID_ARGUMENT, [&] {
    require(sea, "sea");
    require(x_m, "x_m");
    require(y_m, "y_m");
    if (!sea->projection)
      fail(NEARSHORE_INVALID_ARGUMENT, "this sequence's grid has no map projection (a laboratory grid in local "
                                       "metres); give positions in site metres");
    if (!(std::abs(latitude_deg) <= 90.0) || !(std::abs(longitude_deg) <= 360.0))
      fail(NEARSHORE_INVALID_ARGUMENT, "latitude " + std::to_string(latitude_deg) + ", longitude " +
                                           std::to_string(longitude_deg) + " is not a place; give degrees (WGS 84)");
    nearshore::ProjectedPoint point;
    try {
      point = sea->projection->forward({longitude_deg, latitude_deg});
    } catch (const std::exception& error) {
      // GeographicLib refuses a place far outside the grid's UTM zone: the caller's place, not a bug.
      fail(NEARSHORE_INVALID_ARGUMENT, fmt::format("latitude {:.6g}, longitude {:.6g} cannot be put in this sequence's "
                                                   "map projection ({}); give a place near the harbour",
                                                   latitude_deg, longitude_deg, error.what()));
    }
    const nearshore::GridGeometry& geometry = sea->engine().manifest().geometry;
    *x_m = point.x_m - geometry.origin_x_m;
    *y_m = point.y_m - geometry.origin_y_m;
  });
}

nearshore_status nearshore_sea_stats(const nearshore_sea* sea, nearshore_stats* stats) {
  return guarded(NEARSHORE_INTERNAL_ERROR, [&] {
    require(sea, "sea");
    nearshore_stats* host = require(stats, "stats");
    // Filled whole here, then copied up to the host's struct_size (a version 4 struct ends at message).
    constexpr std::size_t kVersion4Size = offsetof(nearshore_stats, harbour_underruns);
    if (host->struct_size != sizeof(nearshore_stats) && host->struct_size != kVersion4Size)
      fail(NEARSHORE_INVALID_ARGUMENT, "nearshore_stats.struct_size = " + std::to_string(host->struct_size) +
                                           " must be sizeof(nearshore_stats)");
    const uint32_t host_size = host->struct_size;
    nearshore_stats full{};
    stats = &full;
    stats->struct_size = host_size;
    const nearshore::runtime::StreamingStats s = sea->engine().stats();
    stats->display_time_s = sea->snapshot().display_time_s;
    stats->ring_filled = s.ring_fill;
    stats->ring_capacity = s.ring_capacity;
    stats->underruns = static_cast<uint64_t>(s.underruns);
    stats->keyframes_decoded = static_cast<uint64_t>(s.keyframes_decoded);
    stats->decode_frames_per_s = s.decode_frames_per_s();
    stats->decode_real_time_multiple = s.decode_real_time_multiple();
    stats->bad_frames_held = static_cast<uint64_t>(s.bad_frames_held);
    stats->transitions_taken = static_cast<uint64_t>(s.transitions_taken);
    stats->plan_step = s.plan_step;
    stats->crossfading = s.in_crossfade ? 1 : 0;
    // The kind, which fits the field; the full description (seed, loop length) is longer than 31
    // characters and stays with the C++ StreamingStats::plan.
    copy_text(stats->plan_name, std::string(nearshore::runtime::plan_kind_name(sea->engine().plan().kind())));
    copy_text(stats->message, s.last_message);
    stats->harbour_underruns = static_cast<uint64_t>(s.harbour_underruns);
    stats->deep_underruns = static_cast<uint64_t>(s.deep_underruns);
    stats->synchronous_keyframes = static_cast<uint64_t>(s.synchronous_keyframes);
    stats->last_advance_planned = s.last_advance_planned ? 1 : 0;
    stats->time_mode = sea->time_mode;
    std::memcpy(host, &full, host_size);
  });
}

nearshore_status nearshore_sea_query(const nearshore_sea* sea, const double* xy_m, size_t count,
                                     nearshore_surface_sample* samples) {
  return guarded(NEARSHORE_INTERNAL_ERROR, [&] {
    require(sea, "sea");
    if (count == 0) return;
    checked_count(count);
    query(sea->snapshot(), require(xy_m, "xy_m"), count, require(samples, "samples"));
  });
}

nearshore_status nearshore_sea_query_at(const nearshore_sea* sea, double time_s, const double* xy_m, size_t count,
                                        nearshore_surface_sample* samples) {
  return guarded(NEARSHORE_IO_ERROR, [&] {
    require(sea, "sea");
    checked_time(time_s, "time_s");
    if (count == 0) return;
    checked_count(count);
    query(sea->engine().snapshot_at(time_s), require(xy_m, "xy_m"), count, require(samples, "samples"));
  });
}

nearshore_status nearshore_sea_copy_harbour_elevation(const nearshore_sea* sea, float* elevation_m, size_t capacity) {
  return guarded(NEARSHORE_INTERNAL_ERROR, [&] {
    require(sea, "sea");
    require(elevation_m, "elevation_m");
    const nearshore::runtime::SurfaceSnapshot snapshot = sea->snapshot();
    const nearshore::GridGeometry& geometry = sea->engine().manifest().geometry;
    if (capacity < geometry.cell_count())
      fail(NEARSHORE_INVALID_ARGUMENT, "capacity = " + std::to_string(capacity) + " floats; the harbour has " +
                                           std::to_string(geometry.cell_count()) + " cells (columns x rows)");
    // Joined in time as the renderer and the queries join them (runtime/surface_snapshot.hpp).
    nearshore::runtime::shown_harbour_elevation(snapshot, elevation_m);
  });
}

nearshore_status nearshore_sea_query_vertical_velocity(const nearshore_sea* sea, const double* xy_m, size_t count,
                                                       float* vertical_velocity_m_s) {
  return guarded(NEARSHORE_INTERNAL_ERROR, [&] {
    require(sea, "sea");
    if (count == 0) return;
    checked_count(count);
    require(xy_m, "xy_m");
    require(vertical_velocity_m_s, "vertical_velocity_m_s");
    const std::vector<nearshore::runtime::SurfaceState> states = surface_states(sea->snapshot(), xy_m, count);
    for (std::size_t i = 0; i < count; ++i) vertical_velocity_m_s[i] = static_cast<float>(states[i].vertical_velocity_m_s);
  });
}

void nearshore_camera_init(nearshore_camera* camera) {
  if (!camera) return;
  *camera = {};
  camera->struct_size = sizeof(nearshore_camera);
  camera->eye_m[2] = 100.0;
  camera->target_m[1] = 100.0;
  camera->vertical_fov_deg = 45.0;
  camera->sun_azimuth_deg = 200.0;
  camera->sun_elevation_deg = 35.0;
}

nearshore_status nearshore_renderer_create(nearshore_sea* sea, nearshore_grid grid,
                                           nearshore_gl_proc_address get_proc_address, nearshore_renderer** renderer) {
  return guarded(NEARSHORE_GL_ERROR, [&] {
    require(sea, "sea");
    require(renderer, "renderer");
    *renderer = nullptr;
    nearshore::playback::load_opengl(require(get_proc_address, "get_proc_address"));
    nearshore::playback::RendererSettings settings;
    switch (grid) {
      case NEARSHORE_GRID_RADIAL: settings.grid = nearshore::playback::GridKind::radial; break;
      case NEARSHORE_GRID_QUADTREE: settings.grid = nearshore::playback::GridKind::quadtree; break;
      case NEARSHORE_GRID_PROJECTED: settings.grid = nearshore::playback::GridKind::projected; break;
      default:
        fail(NEARSHORE_INVALID_ARGUMENT, "grid = " + std::to_string(int(grid)) + " is not a nearshore_grid");
    }
    auto created = std::make_unique<nearshore_renderer>();
    created->sea = sea;
    created->renderer = std::make_unique<nearshore::playback::WaterRenderer>(settings);
    *renderer = created.release();
  });
}

void nearshore_renderer_destroy(nearshore_renderer* renderer) {
  try {
    delete renderer;
  } catch (...) {
    nearshore::capi::last_error() = "nearshore_renderer_destroy: the GL objects could not be freed (was the context current?)";
  }
}

nearshore_status nearshore_renderer_draw(nearshore_renderer* renderer, const nearshore_camera* camera, int width_px,
                                         int height_px) {
  return guarded(NEARSHORE_GL_ERROR, [&] {
    require(renderer, "renderer");
    require(camera, "camera");
    if (camera->struct_size != sizeof(nearshore_camera))
      fail(NEARSHORE_INVALID_ARGUMENT, "nearshore_camera.struct_size must be sizeof(nearshore_camera); call nearshore_camera_init");
    if (width_px < 1 || height_px < 1 || width_px > 16384 || height_px > 16384)
      fail(NEARSHORE_INVALID_ARGUMENT, "the viewport " + std::to_string(width_px) + " x " + std::to_string(height_px) +
                                           " px is outside 1-16384 px");
    nearshore::playback::Camera view;
    for (int k = 0; k < 3; ++k) view.eye_m[k] = camera->eye_m[k], view.target_m[k] = camera->target_m[k];
    view.vertical_field_of_view_deg = camera->vertical_fov_deg;
    view.near_m = camera->near_m;
    view.far_m = camera->far_m;
    nearshore::playback::Lighting lighting = renderer->lighting;
    if (!renderer->sun_from_time) {
      lighting.sun_azimuth_deg = camera->sun_azimuth_deg;
      lighting.sun_elevation_deg = camera->sun_elevation_deg;
    }
    const nearshore::runtime::SurfaceSnapshot snapshot = renderer->sea->snapshot();
    if (snapshot.deep_from)
      if (const auto onset = renderer->whitecaps.update(snapshot.deep_from->cascades,
                                                        snapshot.site ? snapshot.site->choppiness : 1.0, lighting.wind_speed_m_s))
        renderer->jacobian_foam_onset = onset->jacobian_foam_onset;
    lighting.jacobian_foam_onset = renderer->jacobian_foam_onset;
    renderer->renderer->stage_upcoming(renderer->sea->engine());
    const nearshore::playback::SurfaceLayers* layers =
        renderer->fleet ? &nearshore::capi::fleet_surface_layers(*renderer->fleet) : nullptr;
    renderer->renderer->render(snapshot, view, lighting, width_px, height_px, {}, layers);
    renderer->renderer->blit_to_window(width_px, height_px);
    renderer->last_width_px = width_px;
    renderer->last_height_px = height_px;
  });
}

nearshore_status nearshore_renderer_set_fleet(nearshore_renderer* renderer, nearshore_fleet* fleet) {
  return guarded(NEARSHORE_INVALID_ARGUMENT, [&] {
    require(renderer, "renderer");
    if (fleet && nearshore::capi::fleet_sea(*fleet) != renderer->sea)
      fail(NEARSHORE_INVALID_ARGUMENT, "nearshore_renderer_set_fleet: the fleet is bound to another sea than the "
                                       "renderer's; create the fleet with the renderer's sea");
    renderer->fleet = fleet;
  });
}

void nearshore_lighting_init(nearshore_lighting* lighting) {
  if (!lighting) return;
  const nearshore::playback::Lighting defaults;
  *lighting = nearshore_lighting{};
  lighting->struct_size = sizeof(nearshore_lighting);
  lighting->latitude_deg = lighting->longitude_deg = std::numeric_limits<double>::quiet_NaN();
  lighting->atmospheric_turbidity = defaults.atmospheric_turbidity;
  lighting->chlorophyll_mg_m3 = defaults.water.chlorophyll_mg_m3;
  lighting->cdom_absorption_440_per_m = defaults.water.cdom_absorption_440_per_m;
  lighting->water_turbidity_ntu = defaults.water.turbidity_ntu;
  lighting->wind_speed_m_s = defaults.wind_speed_m_s;
  lighting->wind_direction_deg = 0.0;
  lighting->exposure_compensation = defaults.exposure_compensation;
  lighting->local_reflections = 1;
  lighting->cloud_cover = defaults.cloud_cover;
  lighting->visibility_m = defaults.visibility_m;
  lighting->fog_top_m = defaults.fog_top_m;
}

namespace {
// A number of nearshore_lighting inside its documented range, or the call fails naming the field.
double lighting_field(double value, const char* field, double low, double high) {
  if (!std::isfinite(value) || value < low || value > high)
    fail(NEARSHORE_INVALID_ARGUMENT, std::string("nearshore_lighting.") + field + " = " + std::to_string(value) +
                                         " is outside " + std::to_string(low) + " .. " + std::to_string(high));
  return value;
}

nearshore::playback::UtcTime parse_utc(const char* text, const char* field) {
  try {
    return nearshore::playback::UtcTime::parse(text);
  } catch (const std::exception& e) {
    fail(NEARSHORE_INVALID_ARGUMENT, std::string(field) + " = \"" + text + "\" is not a UTC time like " +
                                         "2026-06-21T11:00:00Z: " + e.what());
  }
}
}  // namespace

nearshore_status nearshore_renderer_set_lighting(nearshore_renderer* renderer, const nearshore_lighting* lighting) {
  return guarded(NEARSHORE_INVALID_ARGUMENT, [&] {
    require(renderer, "renderer");
    require(lighting, "lighting");
    // Version 6 ended at local_reflections (padded to the doubles' alignment): clear air.
    constexpr std::size_t kVersion6Size = offsetof(nearshore_lighting, cloud_cover);
    if (lighting->struct_size != sizeof(nearshore_lighting) && lighting->struct_size != kVersion6Size)
      fail(NEARSHORE_INVALID_ARGUMENT,
           "nearshore_lighting.struct_size must be sizeof(nearshore_lighting); call nearshore_lighting_init");
    const bool has_weather = lighting->struct_size >= sizeof(nearshore_lighting);
    // Built aside and swapped in whole, so a refused field leaves the previous lighting.
    nearshore::playback::Lighting next = renderer->lighting;
    next.atmospheric_turbidity = lighting_field(lighting->atmospheric_turbidity, "atmospheric_turbidity", 1.7, 10.0);
    next.water.chlorophyll_mg_m3 = lighting_field(lighting->chlorophyll_mg_m3, "chlorophyll_mg_m3", 0.0, 100.0);
    next.water.cdom_absorption_440_per_m =
        lighting->cdom_absorption_440_per_m < 0
            ? -1.0
            : lighting_field(lighting->cdom_absorption_440_per_m, "cdom_absorption_440_per_m", 0.0, 50.0);
    next.water.turbidity_ntu = lighting_field(lighting->water_turbidity_ntu, "water_turbidity_ntu", 0.0, 1000.0);
    next.wind_speed_m_s = lighting_field(lighting->wind_speed_m_s, "wind_speed_m_s", 0.0, 60.0);
    next.wind_direction_rad =
        travel_direction_rad(lighting_field(lighting->wind_direction_deg, "wind_direction_deg", -360.0, 720.0));
    next.exposure_compensation = lighting_field(lighting->exposure_compensation, "exposure_compensation", 1e-3, 1e3);
    const nearshore::playback::Lighting clear_air;
    next.cloud_cover = has_weather ? lighting_field(lighting->cloud_cover, "cloud_cover", 0.0, 1.0) : clear_air.cloud_cover;
    next.visibility_m = has_weather ? lighting_field(lighting->visibility_m, "visibility_m", 0.0, 1e6) : clear_air.visibility_m;
    next.fog_top_m = has_weather ? lighting_field(lighting->fog_top_m, "fog_top_m", 0.0, 1e4) : clear_air.fog_top_m;
    bool sun_from_time = false;
    const std::string utc(lighting->utc_iso8601, strnlen(lighting->utc_iso8601, sizeof(lighting->utc_iso8601)));
    if (!utc.empty()) {
      const nearshore::playback::UtcTime time = parse_utc(utc.c_str(), "nearshore_lighting.utc_iso8601");
      nearshore::LonLat place{lighting->longitude_deg, lighting->latitude_deg};
      if (std::isnan(place.latitude_deg) || std::isnan(place.longitude_deg)) {
        if (!renderer->sea->projection)
          fail(NEARSHORE_INVALID_ARGUMENT, "nearshore_lighting.utc_iso8601 needs a place, and this sea's grid has no "
                                           "map projection (local metres): give latitude_deg and longitude_deg");
        const nearshore::GridGeometry& g = renderer->sea->engine().manifest().geometry;
        place = renderer->sea->projection->reverse({g.origin_x_m + 0.5 * g.width_m(), g.origin_y_m + 0.5 * g.height_m()});
      } else {
        lighting_field(place.latitude_deg, "latitude_deg", -90.0, 90.0);
        lighting_field(place.longitude_deg, "longitude_deg", -180.0, 360.0);
      }
      next.set_sun_for(place.latitude_deg, place.longitude_deg, time);
      sun_from_time = true;
    }
    renderer->renderer->settings().local_reflections = lighting->local_reflections != 0;
    renderer->lighting = next;
    renderer->sun_from_time = sun_from_time;
  });
}

nearshore_status nearshore_sun_position(double latitude_deg, double longitude_deg, const char* utc_iso8601,
                                        double* azimuth_deg, double* elevation_deg) {
  return guarded(NEARSHORE_INVALID_ARGUMENT, [&] {
    require(azimuth_deg, "azimuth_deg");
    require(elevation_deg, "elevation_deg");
    lighting_field(latitude_deg, "latitude_deg", -90.0, 90.0);
    lighting_field(longitude_deg, "longitude_deg", -180.0, 360.0);
    const nearshore::playback::UtcTime time = parse_utc(require(utc_iso8601, "utc_iso8601"), "utc_iso8601");
    const nearshore::playback::SunPosition sun = nearshore::playback::sun_position(latitude_deg, longitude_deg, time);
    *azimuth_deg = sun.azimuth_deg;
    *elevation_deg = sun.elevation_deg;
  });
}

nearshore_status nearshore_renderer_read_pixels(nearshore_renderer* renderer, int width_px, int height_px,
                                                uint8_t* rgba) {
  return guarded(NEARSHORE_GL_ERROR, [&] {
    require(renderer, "renderer");
    require(rgba, "rgba");
    if (width_px != renderer->last_width_px || height_px != renderer->last_height_px)
      fail(NEARSHORE_INVALID_ARGUMENT, "read " + std::to_string(width_px) + " x " + std::to_string(height_px) +
                                           " px, but the last draw was " + std::to_string(renderer->last_width_px) +
                                           " x " + std::to_string(renderer->last_height_px) + " px");
    const nearshore::Image image = renderer->renderer->read_pixels();
    const std::vector<float>& rgb = image.pixels();  // linear 0..1 display values, 3 per pixel, row 0 at the top
    const std::size_t count = static_cast<std::size_t>(width_px) * static_cast<std::size_t>(height_px);
    for (std::size_t i = 0; i < count; ++i) {
      for (int c = 0; c < 3; ++c)
        rgba[4 * i + c] = static_cast<uint8_t>(std::lround(255.f * std::clamp(rgb[3 * i + c], 0.f, 1.f)));
      rgba[4 * i + 3] = 255;
    }
  });
}

nearshore_status nearshore_renderer_upload(nearshore_renderer* renderer, nearshore_gl_textures* textures) {
  return guarded(NEARSHORE_GL_ERROR, [&] {
    require(renderer, "renderer");
    require(textures, "textures");
    constexpr std::size_t kVersion5Size = offsetof(nearshore_gl_textures, harbour_elevation_rate);
    if (textures->struct_size != sizeof(nearshore_gl_textures) && textures->struct_size != kVersion5Size)
      fail(NEARSHORE_INVALID_ARGUMENT, "nearshore_gl_textures.struct_size must be sizeof(nearshore_gl_textures)");
    const bool version_6 = textures->struct_size == sizeof(nearshore_gl_textures);
    const nearshore::playback::GpuTextures& gpu = renderer->renderer->upload(renderer->sea->snapshot());
    if (gpu.cascade_count > 8)
      fail(NEARSHORE_INTERNAL_ERROR, "the deep water has " + std::to_string(gpu.cascade_count) + " cascades; the C API carries 8");
    for (int k = 0; k < 2; ++k) {
      textures->harbour_elevation[k] = gpu.harbour_elevation[k];
      textures->harbour_breaking[k] = gpu.harbour_breaking[k];
      textures->deep_elevation[k] = gpu.deep_elevation[k];
      textures->deep_displacement_x[k] = gpu.deep_displacement_x[k];
      textures->deep_displacement_y[k] = gpu.deep_displacement_y[k];
      textures->deep_slope_x[k] = gpu.deep_slope_x[k];
      textures->deep_slope_y[k] = gpu.deep_slope_y[k];
    }
    textures->harbour_fraction = static_cast<float>(gpu.harbour_fraction);
    textures->cascade_count = gpu.cascade_count;
    textures->deep_grid_size = gpu.deep_grid_size;
    for (int c = 0; c < 8; ++c) textures->cascade_tile_m[c] = c < gpu.cascade_count ? gpu.tile_lengths_m[static_cast<std::size_t>(c)] : 0.f;
    textures->deep_water_fraction = static_cast<float>(gpu.deep_fraction);
    if (version_6) {
      for (int k = 0; k < 2; ++k) textures->harbour_elevation_rate[k] = gpu.harbour_elevation_rate[k];
      textures->harbour_has_rates = gpu.harbour_has_rates ? 1 : 0;
      textures->frame_interval_s = static_cast<float>(gpu.frame_interval_s);
    }
  });
}

}  // extern "C"
