// The ships of the C API (include/nearshore.h, nearshore_fleet_*) over ships::ShipFleet
// (docs/ships.md): a fleet bound to a sea steps on the snapshot the renderer draws; its bow waves
// join the CPU queries. Every entry point is guarded (c_boundary.hpp): no exception crosses.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <deque>
#include <filesystem>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "c_boundary.hpp"
#include "nearshore/ships/fleet_layers.hpp"
#include "nearshore/ships/generic_hulls.hpp"
#include "nearshore/ships/hull_file.hpp"
#include "nearshore/ships/ship_fleet.hpp"
#include "nearshore/ships/ship_limits.hpp"

struct nearshore_fleet {
  const nearshore_sea* sea = nullptr;
  nearshore::ships::ShipFleet ships;
  nearshore::ships::FleetLayers layers;  // the hulls as drawn; the layers nearshore_renderer_draw adds
  std::deque<std::string> events;  // taken from the fleet after each step, handed out one by one
  std::deque<nearshore::ships::ContactEvent> contacts;  // likewise
};

namespace {
using namespace nearshore::capi;
namespace ships = nearshore::ships;

constexpr double kDegree = std::numbers::pi / 180.0;

ships::Ship& ship_of(nearshore_fleet* fleet, int ship) {
  require(fleet, "fleet");
  if (ship < 0 || static_cast<std::size_t>(ship) >= fleet->ships.size())
    fail(NEARSHORE_INVALID_ARGUMENT, "ship = " + std::to_string(ship) + " is not a ship of this fleet (it has " +
                                         std::to_string(fleet->ships.size()) + "); ships are numbered from 0");
  return fleet->ships.ship(static_cast<std::size_t>(ship));
}
const ships::Ship& ship_of(const nearshore_fleet* fleet, int ship) {
  return ship_of(const_cast<nearshore_fleet*>(fleet), ship);
}

std::vector<Eigen::Vector2d> route_of(const double* xy_m, std::size_t count, const char* parameter) {
  std::vector<Eigen::Vector2d> route;
  if (count == 0) return route;
  require(xy_m, parameter);
  if (count > 100000)
    fail(NEARSHORE_INVALID_ARGUMENT, std::string(parameter) + " has " + std::to_string(count) + " waypoints; give at most 100000");
  for (std::size_t k = 0; k < count; ++k) {
    const ships::ParameterRange& site = ships::limits::kSiteCoordinate;
    for (int axis = 0; axis < 2; ++axis)
      if (!(xy_m[2 * k + axis] >= site.min && xy_m[2 * k + axis] <= site.max))
        fail(NEARSHORE_INVALID_ARGUMENT, "waypoint " + std::to_string(k) + " of " + parameter + " has " +
                                             (axis == 0 ? "x = " : "y = ") + ships::format_value(xy_m[2 * k + axis]) +
                                             " m, outside [-1e6, 1e6] m: " + site.reason + "; give site metres");
    route.emplace_back(xy_m[2 * k], xy_m[2 * k + 1]);
  }
  return route;
}

// The hull of `options`: a generic hull by name, else a mesh file (missing: an I/O error; open,
// inverted or unreadable: a format error, the loader's message naming the file).
ships::HullMesh hull_of(const nearshore_ship_options& options, const std::string& name) {
  const std::string hull = options.hull ? options.hull : "";
  if (hull.empty())
    fail(NEARSHORE_INVALID_ARGUMENT, "ship '" + name + "': nearshore_ship_options.hull is empty; give \"tug\", "
                                     "\"wigley\", \"box_barge\" or a mesh file");
  ships::GenericHullDimensions dimensions;
  dimensions.length_m = options.length_m;
  dimensions.beam_m = options.beam_m;
  dimensions.depth_m = options.depth_m;
  dimensions.draft_m = options.mass_kg > 0.0 ? 0.0 : options.draft_m;
  if (std::optional<ships::HullMesh> generic = ships::generic_hull(hull, dimensions)) return std::move(*generic);
  if (!std::filesystem::is_regular_file(hull))
    fail(NEARSHORE_IO_ERROR, "ship '" + name + "': " + hull + ": no such hull mesh file; give \"tug\", \"wigley\", "
                             "\"box_barge\" or the path of an OBJ, PLY, glTF or STL file");
  try {
    return ships::load_hull_mesh(hull);
  } catch (const nearshore::Error& error) {
    fail(NEARSHORE_FORMAT_ERROR, "ship '" + name + "': " + error.what());
  }
}

// A field of nearshore_ship_options in its range (ships/ship_limits.hpp), else INVALID_ARGUMENT
// naming the ship, the field, the range and its reason.
void check_field(const std::string& ship, const char* field, double value, const ships::ParameterRange& range) {
  try {
    ships::require_in_range("ship '" + ship + "'", std::string("nearshore_ship_options.") + field, value, range);
  } catch (const nearshore::Error& error) {
    fail(NEARSHORE_INVALID_ARGUMENT, error.what());
  }
}

// Every field in its range before the hull is made (a 1e9 m hull would be lofted and cut first).
void check_options(const nearshore_ship_options& o, const std::string& name) {
  namespace limits = ships::limits;
  if (o.length_m != 0.0) check_field(name, "length_m", o.length_m, limits::kLength);
  if (o.beam_m != 0.0) check_field(name, "beam_m", o.beam_m, limits::kBeam);
  if (o.depth_m != 0.0) check_field(name, "depth_m", o.depth_m, limits::kDepth);
  if (o.mass_kg != 0.0)
    check_field(name, "mass_kg", o.mass_kg, limits::kMass);
  else if (o.draft_m != 0.0)
    check_field(name, "draft_m", o.draft_m, limits::kDraft);
  else
    fail(NEARSHORE_INVALID_ARGUMENT, "ship '" + name + "': neither nearshore_ship_options.mass_kg nor draft_m is "
                                     "given; give the displacement or the draft");
  if (!o.use_lat_lon) {
    check_field(name, "x_m", o.x_m, limits::kSiteCoordinate);
    check_field(name, "y_m", o.y_m, limits::kSiteCoordinate);
  }
  if (!std::isfinite(o.heading_deg))
    fail(NEARSHORE_INVALID_ARGUMENT, "ship '" + name + "': nearshore_ship_options.heading_deg = " +
                                         ships::format_value(o.heading_deg) + " is not a compass heading; give degrees");
  // The speed's upper limit depends on the hull's length (ShipFleet::add_ship checks it); here
  // only what no hull allows.
  const double speed_cap = limits::kSpeed.max;
  check_field(name, "initial_speed_m_s", o.initial_speed_m_s, {-speed_cap, speed_cap, "m/s", limits::kSpeed.reason});
  if (o.hull_points != 0) check_field(name, "hull_points", o.hull_points, limits::kHullPoints);
  if (o.bow_wave != 0 && o.bow_wave_cells != 0) check_field(name, "bow_wave_cells", o.bow_wave_cells, limits::kBowWaveCells);
}

ships::ShipDefinition definition_of(const nearshore_fleet& fleet, const nearshore_ship_options& options) {
  ships::ShipDefinition d;
  d.name = options.name && *options.name ? options.name : "ship " + std::to_string(fleet.ships.size());
  check_options(options, d.name);
  d.hull = hull_of(options, d.name);
  if (options.mass_kg != 0.0)
    d.loading.mass_kg = options.mass_kg;
  else
    d.loading.draft_m = options.draft_m;
  if (options.use_lat_lon) {
    const nearshore_status status =
        nearshore_site_from_lat_lon(fleet.sea, options.latitude_deg, options.longitude_deg, &d.x_m, &d.y_m);
    if (status != NEARSHORE_OK) fail(status, "ship '" + d.name + "': " + last_error());
  } else {
    d.x_m = options.x_m;
    d.y_m = options.y_m;
  }
  d.heading_deg = options.heading_deg;
  d.initial_speed_m_s = options.initial_speed_m_s;
  switch (options.order) {
    case NEARSHORE_ORDER_MANUAL: break;
    case NEARSHORE_ORDER_ENGINE:
      if (!(std::abs(options.engine_order) <= 1.0))
        fail(NEARSHORE_INVALID_ARGUMENT, "ship '" + d.name + "': nearshore_ship_options.engine_order = " +
                                             ships::format_value(options.engine_order) +
                                             " is outside [-1, 1] (full astern .. full ahead)");
      d.orders.engine_order = options.engine_order;
      break;
    case NEARSHORE_ORDER_SPEED:
      check_field(d.name, "speed_m_s", options.speed_m_s, ships::limits::kSpeed);  // the hull's own limit: add_ship
      d.orders.speed_m_s = options.speed_m_s;
      break;
    default:
      fail(NEARSHORE_INVALID_ARGUMENT, "ship '" + d.name + "': order = " + std::to_string(int(options.order)) +
                                           " is not a nearshore_ship_order");
  }
  d.orders.route_m = route_of(options.route_xy_m, options.route_count, "route_xy_m");
  if (options.hull_points != 0) d.hull_points = options.hull_points;
  d.bow_wave = options.bow_wave != 0;
  if (options.bow_wave_cells != 0) d.bow_wave_options.cells = options.bow_wave_cells;
  d.dispersive_wake = options.dispersive_wake != 0;
  return d;
}

// A ship's height layer (bow-wave grid or dispersive wake) into the C struct, and its heights
// into the caller's buffer when one is given; columns = 0 when the ship has no such layer.
void copy_height_field(const std::optional<ships::BowWaveField>& f, nearshore_bow_wave_field* field, float* heights_m,
                       size_t capacity) {
  require(field, "field");
  if (field->struct_size != sizeof(nearshore_bow_wave_field))
    fail(NEARSHORE_INVALID_ARGUMENT, "nearshore_bow_wave_field.struct_size must be sizeof(nearshore_bow_wave_field)");
  field->columns = field->rows = 0;
  field->origin_x_m = field->origin_y_m = 0.0;
  field->spacing_m = 0.0;
  field->serial = 0;
  if (!f) return;
  field->columns = f->columns;
  field->rows = f->rows;
  field->origin_x_m = f->origin_x_m;
  field->origin_y_m = f->origin_y_m;
  field->spacing_m = f->spacing_m;
  field->serial = f->serial;
  if (!heights_m) return;
  const std::size_t cells = static_cast<std::size_t>(f->columns) * static_cast<std::size_t>(f->rows);
  if (capacity < cells)
    fail(NEARSHORE_INVALID_ARGUMENT, "capacity = " + std::to_string(capacity) + " floats; the layer has " +
                                         std::to_string(cells) + " cells (columns x rows)");
  std::copy(f->heights_m->begin(), f->heights_m->begin() + static_cast<std::ptrdiff_t>(cells), heights_m);
}

// A ship's wave layers in the order of nearshore_fleet_wave_layer: 0 the shallow-water grid, 1 the
// dispersive layer (ShipFleet makes the second only with the first). The shown weights come from the
// fleet's blend (Ship::dispersive_weight, 0 before the first step), so they sum to 1 from the start;
// after a step they are the weights already in each layer's heights.
int wave_layer_count(const ships::Ship& s) { return s.bow_wave() == nullptr ? 0 : s.dispersive_wake() == nullptr ? 1 : 2; }

struct WaveLayer {
  nearshore_wave_layer_kind kind;
  double shown_weight;
  ships::BowWaveField field;
};

WaveLayer wave_layer_of(const ships::Ship& s, int ship, int layer) {
  const int count = wave_layer_count(s);
  if (layer < 0 || layer >= count)
    fail(NEARSHORE_INVALID_ARGUMENT, "layer = " + std::to_string(layer) + " is not a wave layer of ship " +
                                         std::to_string(ship) + " ('" + s.name() + "' has " + std::to_string(count) +
                                         "; nearshore_fleet_wave_layer_count gives it); layers are numbered from 0");
  if (s.dispersive_wake() == nullptr) return {NEARSHORE_WAVE_LAYER_SHALLOW_WATER, 1.0, s.bow_wave()->field()};
  const double dispersive = s.dispersive_weight();
  if (layer == 0) return {NEARSHORE_WAVE_LAYER_SHALLOW_WATER, 1.0 - dispersive, s.bow_wave()->field()};
  return {NEARSHORE_WAVE_LAYER_DISPERSIVE, dispersive, s.dispersive_wake()->field()};
}

// The fleet's bow waves added to sea samples: elevation, and the normal tilted by the bow wave's
// slope (central differences over 0.25 m, below a bow-wave cell: 4 ship lengths / 128 cells is
// 0.6 m even for a 20 m hull, so the difference sees the bilinear field's own slope).
void add_bow_waves(const ships::ShipFleet& fleet, const double* xy_m, std::size_t count,
                   nearshore_surface_sample* samples) {
  if (fleet.size() == 0) return;
  constexpr double kStepM = 0.25;
  for (std::size_t i = 0; i < count; ++i) {
    const double x = xy_m[2 * i], y = xy_m[2 * i + 1];
    const double bow = fleet.bow_wave_elevation_m(x, y);
    const double slope_x = (fleet.bow_wave_elevation_m(x + kStepM, y) - fleet.bow_wave_elevation_m(x - kStepM, y)) / (2 * kStepM);
    const double slope_y = (fleet.bow_wave_elevation_m(x, y + kStepM) - fleet.bow_wave_elevation_m(x, y - kStepM)) / (2 * kStepM);
    nearshore_surface_sample& s = samples[i];
    if (bow == 0.0 && slope_x == 0.0 && slope_y == 0.0) continue;
    s.elevation_m = static_cast<float>(s.elevation_m + bow);
    // n = (-dz/dx, -dz/dy, 1) / |.|: the sea's slopes from its normal, plus the bow wave's.
    const double nz = std::max(static_cast<double>(s.normal[2]), 1e-6);
    const double sx = -s.normal[0] / nz + slope_x, sy = -s.normal[1] / nz + slope_y;
    const double length = std::sqrt(sx * sx + sy * sy + 1.0);
    s.normal[0] = static_cast<float>(-sx / length);
    s.normal[1] = static_cast<float>(-sy / length);
    s.normal[2] = static_cast<float>(1.0 / length);
  }
}

}  // namespace

namespace nearshore::capi {

const nearshore_sea* fleet_sea(const nearshore_fleet& fleet) { return fleet.sea; }

const nearshore::playback::SurfaceLayers& fleet_surface_layers(nearshore_fleet& fleet) {
  return fleet.layers.update(fleet.ships);
}

}  // namespace nearshore::capi

extern "C" {

void nearshore_ship_options_init(nearshore_ship_options* options) {
  if (!options) return;
  *options = {};
  options->struct_size = sizeof(nearshore_ship_options);
  options->hull = "tug";
  options->draft_m = 3.0;
  options->order = NEARSHORE_ORDER_MANUAL;
  options->bow_wave = 1;
  options->dispersive_wake = 1;  // since version 9 (docs/c-api.md)
}

nearshore_status nearshore_fleet_create(const nearshore_sea* sea, nearshore_fleet** fleet) {
  return guarded(NEARSHORE_INTERNAL_ERROR, [&] {
    require(fleet, "fleet");
    *fleet = nullptr;
    auto created = std::make_unique<nearshore_fleet>();
    created->sea = require(sea, "sea");
    created->ships.set_site(sea->engine().site());
    *fleet = created.release();
  });
}

void nearshore_fleet_destroy(nearshore_fleet* fleet) { delete fleet; }

nearshore_status nearshore_fleet_add_ship(nearshore_fleet* fleet, const nearshore_ship_options* options, int* ship) {
  return guarded(NEARSHORE_INVALID_ARGUMENT, [&] {
    require(fleet, "fleet");
    require(options, "options");
    if (options->struct_size != sizeof(nearshore_ship_options))
      fail(NEARSHORE_INVALID_ARGUMENT, "nearshore_ship_options.struct_size must be sizeof(nearshore_ship_options); "
                                       "call nearshore_ship_options_init");
    const ships::ShipDefinition definition = definition_of(*fleet, *options);
    const std::size_t index = fleet->ships.add_ship(definition);
    fleet->layers.set_hull(index, definition.hull, fleet->ships.ship(index).body().particulars());
    if (ship) *ship = static_cast<int>(index);
  });
}

nearshore_status nearshore_fleet_ship_count(const nearshore_fleet* fleet, int* count) {
  return guarded(NEARSHORE_INTERNAL_ERROR, [&] {
    *require(count, "count") = static_cast<int>(require(fleet, "fleet")->ships.size());
  });
}

nearshore_status nearshore_fleet_set_controls(nearshore_fleet* fleet, int ship, double engine_order, double rudder_deg) {
  return guarded(NEARSHORE_INVALID_ARGUMENT, [&] {
    ships::Ship& s = ship_of(fleet, ship);
    if (!(std::abs(engine_order) <= 1.0))
      fail(NEARSHORE_INVALID_ARGUMENT, "engine_order = " + ships::format_value(engine_order) +
                                           " is outside [-1, 1] (full astern .. full ahead)");
    if (!std::isfinite(rudder_deg))
      fail(NEARSHORE_INVALID_ARGUMENT, "rudder_deg = " + ships::format_value(rudder_deg) +
                                           " is not an angle; give degrees (> 0 to port, clamped to the rudder's limit)");
    s.set_orders({});
    s.manual_controls() = ships::ShipControls{engine_order, rudder_deg * kDegree};
  });
}

nearshore_status nearshore_fleet_set_speed(nearshore_fleet* fleet, int ship, double speed_m_s, const double* route_xy_m,
                                           size_t route_count) {
  return guarded(NEARSHORE_INVALID_ARGUMENT, [&] {
    ships::Ship& s = ship_of(fleet, ship);
    ships::ShipOrders orders;
    orders.speed_m_s = speed_m_s;
    orders.route_m = route_of(route_xy_m, route_count, "route_xy_m");
    s.set_orders(std::move(orders));  // refuses a speed outside [0, the ship's limit] naming speed_m_s
  });
}

nearshore_status nearshore_fleet_step(nearshore_fleet* fleet, double dt_s) {
  return guarded(NEARSHORE_INTERNAL_ERROR, [&] {
    require(fleet, "fleet");
    if (!(dt_s > 0.0 && dt_s <= 1.0))
      fail(NEARSHORE_INVALID_ARGUMENT, "dt_s = " + ships::format_value(dt_s) + " is outside (0, 1] s; step once per displayed frame");
    fleet->ships.step(fleet->sea->snapshot(), dt_s);
    for (std::string& event : fleet->ships.take_events()) fleet->events.push_back(std::move(event));
    for (ships::ContactEvent& contact : fleet->ships.take_contacts()) fleet->contacts.push_back(std::move(contact));
  });
}

nearshore_status nearshore_fleet_next_contact(nearshore_fleet* fleet, nearshore_ship_contact* contact, int* has_contact) {
  return guarded(NEARSHORE_INTERNAL_ERROR, [&] {
    require(fleet, "fleet");
    require(has_contact, "has_contact");
    require(contact, "contact");
    if (contact->struct_size != sizeof(nearshore_ship_contact))
      fail(NEARSHORE_INVALID_ARGUMENT, "nearshore_ship_contact.struct_size must be sizeof(nearshore_ship_contact)");
    *has_contact = fleet->contacts.empty() ? 0 : 1;
    if (fleet->contacts.empty()) return;
    const ships::ContactEvent& e = fleet->contacts.front();
    *contact = {};
    contact->struct_size = sizeof(nearshore_ship_contact);
    contact->ship = static_cast<int>(e.ship_index);
    contact->began = e.began ? 1 : 0;
    contact->structure = e.structure;
    contact->wall = e.wall ? 1 : 0;
    contact->porosity = e.porosity;
    contact->x_m = e.position_m.x();
    contact->y_m = e.position_m.y();
    contact->z_m = e.position_m.z();
    contact->normal[0] = e.normal.x();
    contact->normal[1] = e.normal.y();
    contact->closing_speed_m_s = e.closing_speed_m_s;
    contact->time_s = e.time_s;
    const std::size_t length = std::min(e.description.size(), sizeof contact->description - 1);
    std::memcpy(contact->description, e.description.data(), length);
    contact->description[length] = '\0';
    fleet->contacts.pop_front();
  });
}

nearshore_status nearshore_fleet_ship_pose(const nearshore_fleet* fleet, int ship, nearshore_ship_pose* pose) {
  return guarded(NEARSHORE_INTERNAL_ERROR, [&] {
    const ships::Ship& s = ship_of(fleet, ship);
    require(pose, "pose");
    if (pose->struct_size != sizeof(nearshore_ship_pose))
      fail(NEARSHORE_INVALID_ARGUMENT, "nearshore_ship_pose.struct_size must be sizeof(nearshore_ship_pose)");
    const ships::ShipState& state = s.body().state();
    pose->x_m = state.position_m.x();
    pose->y_m = state.position_m.y();
    pose->z_m = state.position_m.z();
    const Eigen::Quaterniond q = state.orientation.normalized();
    pose->orientation[0] = q.w();
    pose->orientation[1] = q.x();
    pose->orientation[2] = q.y();
    pose->orientation[3] = q.z();
    pose->heading_deg = state.heading_deg();
    pose->roll_deg = state.roll_rad() / kDegree;
    pose->pitch_deg = state.pitch_rad() / kDegree;
    for (int k = 0; k < 3; ++k) {
      pose->velocity_m_s[k] = state.velocity_m_s[k];
      pose->angular_velocity_rad_s[k] = state.angular_velocity_rad_s[k];
    }
    pose->speed_m_s = state.forward_speed_m_s();
    pose->engine_order = s.controls().engine_order;
    pose->rudder_deg = s.controls().rudder_order_rad / kDegree;
    pose->aground = s.status().aground ? 1 : 0;
  });
}

nearshore_status nearshore_fleet_next_event(nearshore_fleet* fleet, char* text, size_t capacity, int* has_event) {
  return guarded(NEARSHORE_INTERNAL_ERROR, [&] {
    require(fleet, "fleet");
    require(has_event, "has_event");
    require(text, "text");
    if (capacity == 0) fail(NEARSHORE_INVALID_ARGUMENT, "capacity = 0; give room for the message (512 chars hold any)");
    *has_event = fleet->events.empty() ? 0 : 1;
    text[0] = '\0';
    if (fleet->events.empty()) return;
    const std::string& event = fleet->events.front();
    const std::size_t length = std::min(event.size(), capacity - 1);
    std::memcpy(text, event.data(), length);
    text[length] = '\0';
    fleet->events.pop_front();
  });
}

nearshore_status nearshore_fleet_wake_decals(const nearshore_fleet* fleet, int ship, nearshore_wake_decal* decals,
                                             size_t capacity, size_t* count) {
  return guarded(NEARSHORE_INTERNAL_ERROR, [&] {
    const ships::Ship& s = ship_of(fleet, ship);
    // The stern wake's decals, then (since version 9) the breaking crests' foam (ship_fleet.hpp).
    const auto& stern = s.wake().decals();
    const auto& crests = s.crest_foam().decals();
    *require(count, "count") = stern.size() + crests.size();
    if (capacity == 0) return;
    require(decals, "decals");
    std::size_t k = 0;
    for (const auto* list : {&stern, &crests})
      for (auto it = list->begin(); it != list->end() && k < capacity; ++it, ++k) {
        decals[k] = {static_cast<float>(it->x_m),      static_cast<float>(it->y_m),
                     static_cast<float>(it->yaw_rad),  static_cast<float>(it->width_m),
                     static_cast<float>(it->length_m), static_cast<float>(it->opacity()),
                     it->variant};
      }
  });
}

nearshore_status nearshore_fleet_bow_wave(const nearshore_fleet* fleet, int ship, nearshore_bow_wave_field* field,
                                          float* heights_m, size_t capacity) {
  return guarded(NEARSHORE_INTERNAL_ERROR, [&] {
    const ships::Ship& s = ship_of(fleet, ship);
    copy_height_field(s.bow_wave() ? std::optional<ships::BowWaveField>(s.bow_wave()->field()) : std::nullopt, field,
                      heights_m, capacity);
  });
}

nearshore_status nearshore_fleet_dispersive_wake(const nearshore_fleet* fleet, int ship, nearshore_bow_wave_field* field,
                                                 float* heights_m, size_t capacity) {
  return guarded(NEARSHORE_INTERNAL_ERROR, [&] {
    const ships::Ship& s = ship_of(fleet, ship);
    copy_height_field(s.dispersive_wake() ? std::optional<ships::BowWaveField>(s.dispersive_wake()->field()) : std::nullopt,
                      field, heights_m, capacity);
  });
}

nearshore_status nearshore_fleet_wave_layer_count(const nearshore_fleet* fleet, int ship, int* count) {
  return guarded(NEARSHORE_INTERNAL_ERROR, [&] {
    const ships::Ship& s = ship_of(fleet, ship);
    *require(count, "count") = wave_layer_count(s);
  });
}

nearshore_status nearshore_fleet_wave_layer(const nearshore_fleet* fleet, int ship, int layer, nearshore_wave_layer* info,
                                            nearshore_bow_wave_field* field, float* heights_m, size_t capacity) {
  return guarded(NEARSHORE_INTERNAL_ERROR, [&] {
    const ships::Ship& s = ship_of(fleet, ship);
    require(info, "info");
    if (info->struct_size != sizeof(nearshore_wave_layer))
      fail(NEARSHORE_INVALID_ARGUMENT, "nearshore_wave_layer.struct_size must be sizeof(nearshore_wave_layer)");
    const WaveLayer chosen = wave_layer_of(s, ship, layer);
    copy_height_field(chosen.field, field, heights_m, capacity);  // checks field before info is written
    info->kind = chosen.kind;
    info->shown_weight = chosen.shown_weight;
  });
}

nearshore_status nearshore_fleet_query(const nearshore_fleet* fleet, const double* xy_m, size_t count,
                                       nearshore_surface_sample* samples) {
  return guarded(NEARSHORE_INTERNAL_ERROR, [&] {
    require(fleet, "fleet");
    if (count == 0) return;
    query(fleet->sea->snapshot(), require(xy_m, "xy_m"), count, require(samples, "samples"));
    add_bow_waves(fleet->ships, xy_m, count, samples);
  });
}

nearshore_status nearshore_fleet_query_at(const nearshore_fleet* fleet, double time_s, const double* xy_m, size_t count,
                                          nearshore_surface_sample* samples) {
  return guarded(NEARSHORE_IO_ERROR, [&] {
    require(fleet, "fleet");
    if (!std::isfinite(time_s) || time_s < 0)
      fail(NEARSHORE_INVALID_ARGUMENT, "time_s = " + std::to_string(time_s) + " is not a display time >= 0 s");
    if (count == 0) return;
    query(fleet->sea->engine().snapshot_at(time_s), require(xy_m, "xy_m"), count, require(samples, "samples"));
    add_bow_waves(fleet->ships, xy_m, count, samples);
  });
}

}  // extern "C"
