#pragma once
// One ship as the viewer shows it: a row of the panel's ship table and of a run's summary
// (`nearshore play --ships`, viewer_ships.hpp). Plain figures, so the panel needs nothing of the ships.
#include <string>

namespace nearshore::viewer {

struct ShipReadout {
  std::string name;
  double x_m = 0, y_m = 0, speed_kn = 0, heading_deg = 0, engine_order = 0, rudder_deg = 0, heel_deg = 0;
  bool aground = false, manual = false;  ///< manual: steered from the keyboard
};

}  // namespace nearshore::viewer
