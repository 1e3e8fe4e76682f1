#include "io/exr/exr_shot_time.h"

#include <OpenEXR/ImfRational.h>

#include <cmath>

namespace kiln {

std::optional<smpte_time_code> smpte_time_code_of(long long frames, double fps) {
  const long long rate = std::llround(fps);
  if (rate < 1 || rate > 60) return std::nullopt;
  const long long day = rate * 24 * 3600;
  const long long in_day = ((frames % day) + day) % day;
  const long long second = in_day / rate;
  const int index = int(in_day % rate);
  smpte_time_code t;
  t.hours = int(second / 3600);
  t.minutes = int(second / 60 % 60);
  t.seconds = int(second % 60);
  t.frame = rate > 30 ? index / 2 : index;
  t.field_phase = rate > 30 && index % 2 == 1;
  return t;
}

frame_rate_fraction frame_rate_of(double fps) {
  for (int nominal : {24, 30, 48, 60, 120})
    if (std::abs(fps - nominal * 1000.0 / 1001.0) < 0.005) return {nominal * 1000, 1001};
  const Imf::Rational r(fps);
  return {r.n, r.d};
}

}  // namespace kiln
