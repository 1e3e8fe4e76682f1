// Pixel reconstruction filters: separable kernels that weight each sample by its distance from a
// pixel centre, pixel = Σ w·L / Σ w (pbrt-v4's filters, chapter 8.8). Pure functions of the
// offset, so every thread computes the same weights. Depends on core only.
#pragma once

#include <optional>
#include <string>

namespace kiln {

enum class filter_kind { box, tent, gaussian, blackman_harris };

struct reconstruction_filter {
  filter_kind kind = filter_kind::box;
  float radius = 0.5f;  // half-width in pixels along each axis; box 0.5 is the pixel's own square
};

// The documented default radius of each kind: box 0.5, tent 1, gaussian 1.5 (sigma = radius/3,
// so 0.5), blackman-harris 2.
float default_filter_radius(filter_kind kind);

// "box", "tent", "gaussian" or "blackman-harris"; empty for anything else.
std::optional<filter_kind> parse_filter_kind(const std::string& name);
const char* filter_name(filter_kind kind);

// The 1D kernel at offset d (pixels) from the centre; 0 outside the radius. Box is 1 on the
// half-open interval [-radius, radius), so with radius 0.5 each sample lands in exactly one pixel.
// Gaussian is exp(-d²/2σ²) minus its value at the radius (so it reaches 0 there, as pbrt does).
// Blackman-Harris is the 4-term window stretched over [-radius, radius]: 1 at 0, 6e-5 at the ends.
float filter_weight_1d(const reconstruction_filter& f, float d);

// The 2D kernel: the product of the 1D kernel along x and along y.
inline float filter_weight(const reconstruction_filter& f, float dx, float dy) {
  return filter_weight_1d(f, dx) * filter_weight_1d(f, dy);
}

// How many pixels beyond its own a sample's weight can reach: those whose centre lies within the
// radius of some point of the pixel, ceil(radius - 0.5). Box 0.5 reaches none, tent 1 and
// gaussian 1.5 one, blackman-harris 2 two.
int filter_reach(const reconstruction_filter& f);

}  // namespace kiln
