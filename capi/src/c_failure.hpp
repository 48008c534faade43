#pragma once
// The failure every C entry point turns into a status (c_boundary.hpp's guarded): thrown inside an
// entry point, caught at its boundary. Apart so that the sea options' checks (sea_options.cpp) and
// their fuzz target need nothing else of the library.
#include <string>
#include <utility>

#include "nearshore.h"

namespace nearshore::capi {

struct Failure {
  nearshore_status status;
  std::string message;
};

[[noreturn]] inline void fail(nearshore_status status, std::string message) { throw Failure{status, std::move(message)}; }

}  // namespace nearshore::capi
