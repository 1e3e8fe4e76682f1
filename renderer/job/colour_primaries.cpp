#include "job/colour_primaries.h"

#include <cmath>

namespace kiln {
namespace {

dvec3 xyz_of(double x, double y) { return {x / y, 1.0, (1.0 - x - y) / y}; }

// The Bradford cone response (Lam 1985), rows as published.
dmat3 bradford() {
  return glm::transpose(dmat3(0.8951, 0.2664, -0.1614, -0.7502, 1.7135, 0.0367, 0.0389, -0.0685, 1.0296));
}

dmat3 adapt(dvec3 from_white, dvec3 to_white) {
  const dmat3 b = bradford();
  const dvec3 s = b * from_white, t = b * to_white;
  return glm::inverse(b) * dmat3(t.x / s.x, 0, 0, 0, t.y / s.y, 0, 0, 0, t.z / s.z) * b;
}

bool near(const dmat3& a, const dmat3& b) {
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r)
      if (std::abs(a[c][r] - b[c][r]) > 1e-5) return false;
  return true;
}

}  // namespace

chromaticities rec709_primaries() { return {{0.64, 0.33, 0.30, 0.60, 0.15, 0.06, 0.3127, 0.3290}}; }
chromaticities ap1_primaries() { return {{0.713, 0.293, 0.165, 0.830, 0.128, 0.044, 0.32168, 0.33767}}; }
chromaticities ap0_primaries() { return {{0.7347, 0.2653, 0.0, 1.0, 0.0001, -0.0770, 0.32168, 0.33767}}; }

dmat3 xyz_from_rgb(const chromaticities& space) {
  const auto& p = space.xy;
  const dmat3 primaries(xyz_of(p[0], p[1]), xyz_of(p[2], p[3]), xyz_of(p[4], p[5]));  // columns
  const dvec3 scale = glm::inverse(primaries) * xyz_of(p[6], p[7]);
  return dmat3(primaries[0] * scale.x, primaries[1] * scale.y, primaries[2] * scale.z);
}

dmat3 rgb_to_rgb(const chromaticities& from, const chromaticities& to) {
  dmat3 m = xyz_from_rgb(from);
  if (from.xy[6] != to.xy[6] || from.xy[7] != to.xy[7])
    m = adapt(xyz_of(from.xy[6], from.xy[7]), xyz_of(to.xy[6], to.xy[7])) * m;
  return glm::inverse(xyz_from_rgb(to)) * m;
}

chromaticities working_primaries(const dmat3& working_from_rec709) {
  for (const chromaticities& known : {rec709_primaries(), ap1_primaries(), ap0_primaries()})
    if (near(working_from_rec709, rgb_to_rgb(rec709_primaries(), known))) return known;
  const dmat3 xyz_from_working = xyz_from_rgb(rec709_primaries()) * glm::inverse(working_from_rec709);
  chromaticities c = rec709_primaries();
  for (int i = 0; i < 3; ++i) {
    const dvec3 p = xyz_from_working[i];
    const double sum = p.x + p.y + p.z;
    c.xy[size_t(2 * i)] = p.x / sum;
    c.xy[size_t(2 * i + 1)] = p.y / sum;
  }
  return c;
}

}  // namespace kiln
