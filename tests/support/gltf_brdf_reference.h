// The glTF BRDF with the material extensions' lobes, in double, written from the specifications'
// formulas (glTF 2.0 appendix B; KHR_materials_specular, _clearcoat, _sheen, _iridescence,
// _anisotropy, _diffuse_transmission): the closed form the lobe-sphere tests hold kiln's shading
// to. Independent of kiln's shading code; the sheen's directional albedo is integrated here by its
// own quadrature (over the light direction, not over the half vector as kiln's table is).
#pragma once

#include "core/math.h"

namespace kiln::testing {

struct reference_material {
  dvec3 base{1.0};
  double metallic = 1.0;
  double roughness = 1.0;
  double ior = 1.5;
  double specular = 1.0;
  dvec3 specular_color{1.0};
  double clearcoat = 0.0;
  double clearcoat_roughness = 0.0;
  dvec3 clearcoat_normal{0.0};  // unit; zero: n
  dvec3 sheen_color{0.0};
  double sheen_roughness = 0.0;
  double iridescence = 0.0;
  double iridescence_ior = 1.3;
  double iridescence_thickness = 400.0;  // nm
  double diffuse_transmission = 0.0;
  dvec3 diffuse_transmission_color{1.0};
  double anisotropy = 0.0;
  dvec3 anisotropy_direction{0.0};  // unit, in the tangent plane; used when anisotropy > 0
};

// f(v, l) for unit n, v, l with n·v > 0; l below the surface reaches only the diffuse transmission.
dvec3 reference_brdf(const reference_material& m, const dvec3& n, const dvec3& v, const dvec3& l);

// The thin-film Fresnel of KHR_materials_iridescence seen from a medium of ior outside_ior (1: air,
// 1.5: under a clearcoat).
dvec3 reference_iridescence_fresnel(double film_ior, double cos_theta, double thickness_nm,
                                    const dvec3& base_f0, double outside_ior = 1.0);

// The white Charlie sheen lobe's directional albedo at cos θ for perceptual roughness r.
double reference_sheen_albedo(double cos_theta, double sheen_roughness);

// IEC 61966-2-1 decoding of an 8-bit code.
double srgb_decode8(int code);

}  // namespace kiln::testing
