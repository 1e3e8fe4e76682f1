// A closed-form (Ferrari) ray-torus solver, for comparison only: kiln renders with the
// root-isolating solver of geometry/torus.cpp. Same re-centred quartic, so the comparison
// isolates the root finder. `polish` adds two Newton steps per root on the quartic.
#pragma once

#include <optional>

#include "core/math.h"

namespace kiln::bench {

std::optional<double> intersect_torus_closed_form(double major_radius, double minor_radius, const dvec3& o,
                                                  const dvec3& d, double tmin, double tmax, bool polish);

}  // namespace kiln::bench
