// libFuzzer target for the fleet API (ctest label `fuzz`, a bounded run): what a host hands
// nearshore_fleet_add_ship / _set_controls / _set_speed / _step reaches ships::ShipFleet as a
// ShipDefinition, orders and controls; here every such value comes from the input: a generic hull
// and its dimensions, the loading (mass or draft), position, heading, initial speed, order, route,
// hull points and bow-wave cells, then frames of controls, orders and time steps, on a small harbour
// with a breakwater and a quay (the seabed and the structures the ships meet). Each value is an
// extreme (0, -1, 1e308, 1e-300, inf, nan, 2^31, the edges of ship_limits.hpp) or raw bytes.
// Every call must end in success or a nearshore::Error that is not an internal error (the fleet's
// divergence guard, the bow-wave grid's step limit): anything else (a crash, a sanitizer report,
// another exception, a timeout, running out of memory) is a finding.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <memory>
#include <string>

#include "nearshore/core/error.hpp"
#include "nearshore/core/harbour_grid.hpp"
#include "nearshore/ships/generic_hulls.hpp"
#include "nearshore/ships/ship_fleet.hpp"

using namespace nearshore;

namespace {

// The input, read front to back; past its end every read is 0.
class Reader {
 public:
  Reader(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}
  std::uint8_t byte() { return at_ < size_ ? data_[at_++] : 0; }
  // An extreme, an edge of a range, a typical value, or 8 raw bytes.
  double number(double typical) {
    static const double kExtremes[] = {0.0,  -1.0, 1e308, 1e-300, std::numeric_limits<double>::infinity(),
                                       -std::numeric_limits<double>::infinity(), std::numeric_limits<double>::quiet_NaN(),
                                       2147483648.0, -0.0, 1e9, 30.0, 15.3, 0.05, 500.0, 80.0, 1e6, -1e6, 2.0};
    const std::uint8_t pick = byte();
    if (pick < 128) return typical;
    if (pick < 128 + std::size(kExtremes)) return kExtremes[pick - 128];
    if (pick < 224) return typical * (pick - 150) / 16.0;
    double raw = 0.0;
    std::uint8_t bytes[8];
    for (auto& b : bytes) b = byte();
    std::memcpy(&raw, bytes, sizeof raw);
    return raw;
  }
  int integer(int typical) {
    const double v = number(typical);
    return std::isfinite(v) && std::abs(v) < 2.1e9 ? static_cast<int>(v) : typical;
  }

 private:
  const std::uint8_t* data_;
  std::size_t size_, at_ = 0;
};

// A 256 x 192 m harbour of 4 m cells, 10 m deep: land in the east (x > 224 m, 2 m high), a
// breakwater (porosity 0.4) along y = 120 m from x = 0 to 120 m, a quay wall (porosity 0) at
// x = 200-204 m.
std::shared_ptr<const runtime::HarbourSite> harbour() {
  static const std::shared_ptr<const runtime::HarbourSite> site = [] {
    GridGeometry geometry;
    geometry.columns = 64;
    geometry.rows = 48;
    geometry.spacing_m = 4.0;
    auto s = std::make_shared<runtime::HarbourSite>();
    s->harbour = HarbourGrid::open_water(geometry, 10.0f);
    for (int j = 0; j < geometry.rows; ++j)
      for (int i = 0; i < geometry.columns; ++i) {
        if (i >= 56) {
          s->harbour.still_water_depth_m(i, j) = -2.0f;
          s->harbour.land(i, j) = kLandCell;
        } else if (i == 50) {
          s->harbour.porosity(i, j) = 0.0f;
        } else if (j == 30 && i < 30) {
          s->harbour.porosity(i, j) = 0.4f;
        }
      }
    s->width_m = 256.0;
    s->height_m = 192.0;
    return s;
  }();
  return site;
}

ships::ShipDefinition definition(Reader& in, int index) {
  static const char* const kHulls[] = {"tug", "wigley", "box_barge"};
  ships::GenericHullDimensions dimensions;
  const char* hull = kHulls[in.byte() % 3];
  dimensions.length_m = in.number(0.0);
  dimensions.beam_m = in.number(0.0);
  dimensions.depth_m = in.number(0.0);
  ships::ShipDefinition d;
  d.name = "fuzz " + std::to_string(index);
  const double mass = in.number(0.0), draft = in.number(1.5);
  dimensions.draft_m = mass != 0.0 ? 0.0 : draft;
  d.hull = *ships::generic_hull(hull, dimensions);  // throws nearshore::Error for a bad dimension
  if (mass != 0.0)
    d.loading.mass_kg = mass;
  else
    d.loading.draft_m = draft;
  d.x_m = in.number(60.0 + 40.0 * index);
  d.y_m = in.number(60.0);
  d.heading_deg = in.number(90.0);
  d.initial_speed_m_s = in.number(2.0);
  switch (in.byte() % 3) {
    case 1: d.orders.engine_order = in.number(0.5); break;
    case 2: d.orders.speed_m_s = in.number(3.0); break;
    default: break;
  }
  const int waypoints = in.byte() % 3;
  for (int k = 0; k < waypoints; ++k) d.orders.route_m.emplace_back(in.number(120.0), in.number(100.0));
  d.hull_points = in.integer(400);
  d.bow_wave = (in.byte() & 7) != 0;
  d.bow_wave_options.cells = in.integer(32);
  d.dispersive_wake = (in.byte() & 7) == 0;
  d.dispersive_wake_options.cells = in.integer(32);
  return d;
}

// A nearshore::Error is the answer to bad input, unless it says it is an internal error (a bug).
template <class Call>
void call(Call&& body) {
  try {
    body();
  } catch (const Error& error) {
    if (std::string(error.what()).find("internal error") != std::string::npos) {
      std::fprintf(stderr, "fuzz_fleet: an internal error from a range-checked input: %s\n", error.what());
      std::abort();
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  Reader in(data, size);
  ships::ShipFleet fleet;
  fleet.set_site(harbour());
  const int ships = 1 + in.byte() % 3;
  for (int k = 0; k < ships; ++k) call([&] { fleet.add_ship(definition(in, k)); });
  const int frames = 1 + in.byte() % 12;
  for (int frame = 0; frame < frames && fleet.size() > 0; ++frame) {
    const std::size_t ship = in.byte() % fleet.size();
    switch (in.byte() % 4) {
      case 1: {
        ships::ShipControls& c = fleet.ship(ship).manual_controls();
        c.engine_order = in.number(1.0);
        c.rudder_order_rad = in.number(0.3);
        call([&] { fleet.ship(ship).set_orders({}); });
        break;
      }
      case 2: {
        ships::ShipOrders orders;
        orders.speed_m_s = in.number(4.0);
        if (in.byte() & 1) orders.route_m.emplace_back(in.number(200.0), in.number(150.0));
        call([&] { fleet.ship(ship).set_orders(std::move(orders)); });
        break;
      }
      default: break;
    }
    const double dt = in.number(1.0 / 30.0);
    call([&] { fleet.step(static_cast<const runtime::SurfaceSampler*>(nullptr), dt); });
    fleet.take_events();
  }
  return 0;
}
