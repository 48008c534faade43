#pragma once
// The incident/reflected separation the tests use is the library's (boussinesq/incident_reflected.hpp):
// these names keep the tests' spelling `nearshore::testing::...`.
#include "nearshore/boussinesq/incident_reflected.hpp"

namespace nearshore::testing {
using boussinesq::harmonic_amplitude;
using boussinesq::IncidentReflected;
using boussinesq::separate_incident_reflected;
}  // namespace nearshore::testing
