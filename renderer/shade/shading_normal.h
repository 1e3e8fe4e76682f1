// Corrections a shading normal needs before a BRDF can use it. An interpolated or normal-mapped
// normal can face away from the viewer near silhouettes and on grazing mapped surfaces; the BRDF is
// then zero and the pixel black. Production renderers bend such a normal toward the geometric one
// just far enough that the view direction's mirror image stays above the surface (the correction
// of the Iray renderer, Keller et al. 2017, appendix A.3, which Cycles also applies). Depends on
// core/math only.
#pragma once

#include "core/math.h"

namespace kiln {

// The normal to shade with: n itself when the mirror image of to_viewer about n lies at least
// min(0.9·(ng·to_viewer), 0.01) above the geometric plane, else n turned toward ng, in the plane
// they span, until it does. All three are unit vectors on the viewer's side (ng·to_viewer > 0,
// n·ng >= 0); the result is unit and faces the viewer (result·to_viewer > 0).
vec3 bend_toward_viewer(const vec3& ng, const vec3& to_viewer, const vec3& n);

}  // namespace kiln
