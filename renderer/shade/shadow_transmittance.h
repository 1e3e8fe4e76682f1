// Shadow rays through see-through surfaces. Whitted's shadow rays are binary; kiln attenuates a
// shadow ray by the transmission colour of every transmissive surface it crosses (the dielectric
// share times the base colour), ignoring the bending and the Fresnel loss at each interface:
// caustics are beyond Whitted shading, and this keeps glass from casting black shadows. An
// alphaMode BLEND surface passes the uncovered share (1 - alpha) of the light as well.
// Works through the accelerator interface (repeated closest-hit queries), so every backend
// behaves the same. Depends on scene, shade and the accelerator interface only.
#pragma once

#include "accel/accelerator.h"
#include "scene/scene.h"
#include "shade/surface.h"

namespace kiln {

// What fraction of light (per channel) a surface passes on to the other side: 0
// for opaque.
vec3 surface_transmittance(const scene& s, const surface_point& sp);

// Transmittance along the segment of shadow ray r: 1 when nothing blocks it, 0
// when something opaque does. crossings counts the extra queries made (for ray
// statistics).
vec3 shadow_transmittance(const scene& s, const accelerator& accel, const ray& r, uint64_t& crossings);

}  // namespace kiln
