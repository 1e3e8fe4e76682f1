#include "support/gltf_brdf_reference.h"

#include <algorithm>
#include <cmath>

namespace kiln::testing {
namespace {

constexpr double dpi = 3.14159265358979323846;

double max3(const dvec3& c) { return std::max({c.x, c.y, c.z}); }
double schlick5(double cos_theta) { return std::pow(1.0 - std::abs(cos_theta), 5.0); }

// GGX D · V (height-correlated Smith), isotropic.
double ggx(double alpha, double nh, double nv, double nl) {
  const double a2 = alpha * alpha;
  const double d = a2 / (dpi * std::pow(nh * nh * (a2 - 1.0) + 1.0, 2.0));
  const double vis =
      0.5 / (nl * std::sqrt(nv * nv * (1.0 - a2) + a2) + nv * std::sqrt(nl * nl * (1.0 - a2) + a2));
  return d * vis;
}

// Anisotropic GGX D · V in the frame (t, b, n): roughness at along t, ab along b.
double ggx_anisotropic(double at, double ab, const dvec3& t, const dvec3& b, const dvec3& n, const dvec3& v,
                       const dvec3& l, const dvec3& h) {
  const double th = glm::dot(t, h), bh = glm::dot(b, h), nh = glm::dot(n, h);
  const double d = 1.0 / (dpi * at * ab * std::pow(th * th / (at * at) + bh * bh / (ab * ab) + nh * nh, 2.0));
  const double lambda_v =
      std::sqrt(at * at * glm::dot(t, v) * glm::dot(t, v) + ab * ab * glm::dot(b, v) * glm::dot(b, v) +
                glm::dot(n, v) * glm::dot(n, v));
  const double lambda_l =
      std::sqrt(at * at * glm::dot(t, l) * glm::dot(t, l) + ab * ab * glm::dot(b, l) * glm::dot(b, l) +
                glm::dot(n, l) * glm::dot(n, l));
  return d * 0.5 / (glm::dot(n, l) * lambda_v + glm::dot(n, v) * lambda_l);
}

double charlie_alpha(double r) { return std::pow(std::clamp(r, 0.07, 1.0), 2.0); }

double charlie_d(double r, double nh) {
  const double inv = 1.0 / charlie_alpha(r);
  return (2.0 + inv) * std::pow(std::max(1.0 - nh * nh, 0.0), 0.5 * inv) / (2.0 * dpi);
}

double charlie_l(double x, double alpha) {
  const double t = (1.0 - alpha) * (1.0 - alpha);
  const auto mix = [t](double a, double b) { return a + (b - a) * t; };
  return mix(21.5473, 25.3245) / (1.0 + mix(3.82987, 3.32435) * std::pow(x, mix(0.19823, 0.16801))) +
         mix(-1.97760, -1.27393) * x + mix(-4.32054, -4.85967);
}

double charlie_lambda(double c, double alpha) {
  return c < 0.5 ? std::exp(charlie_l(c, alpha))
                 : std::exp(2.0 * charlie_l(0.5, alpha) - charlie_l(1.0 - c, alpha));
}

double charlie_v(double r, double nv, double nl) {
  const double alpha = charlie_alpha(r);
  return 1.0 / ((1.0 + charlie_lambda(nv, alpha) + charlie_lambda(nl, alpha)) * 4.0 * nv * nl);
}

dvec3 fresnel(const reference_material& m, const dvec3& f0, double cos_theta) {
  const dvec3 schlick = f0 + (dvec3(1.0) - f0) * schlick5(cos_theta);
  if (m.iridescence <= 0.0) return schlick;
  return glm::mix(schlick,
                  reference_iridescence_fresnel(m.iridescence_ior, cos_theta, m.iridescence_thickness, f0,
                                                m.clearcoat > 0.0 ? 1.5 : 1.0),
                  m.iridescence);
}

dvec3 sensitivity(double opd, const dvec3& shift) {
  const double phase = 2.0 * dpi * opd * 1e-9;
  const dvec3 val(5.4856e-13, 4.4201e-13, 5.2481e-13), pos(1.6810e+06, 1.7953e+06, 2.2084e+06),
      var(4.3278e+09, 9.3046e+09, 6.6121e+09);
  dvec3 xyz;
  for (int c = 0; c < 3; ++c)
    xyz[c] = val[c] * std::sqrt(2.0 * dpi * var[c]) * std::cos(pos[c] * phase + shift[c]) *
             std::exp(-phase * phase * var[c]);
  xyz.x += 9.7470e-14 * std::sqrt(2.0 * dpi * 4.5282e+09) * std::cos(2.2399e+06 * phase + shift[0]) *
           std::exp(-4.5282e+09 * phase * phase);
  xyz /= 1.0685e-7;
  return {3.2404542 * xyz.x - 1.5371385 * xyz.y - 0.4985314 * xyz.z,
          -0.9692660 * xyz.x + 1.8760108 * xyz.y + 0.0415560 * xyz.z,
          0.0556434 * xyz.x - 0.2040259 * xyz.y + 1.0572252 * xyz.z};
}

}  // namespace

double srgb_decode8(int code) {
  const double c = code / 255.0;
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

dvec3 reference_iridescence_fresnel(double film_ior, double cos1, double thickness, const dvec3& base_f0,
                                    double outside_ior) {
  const double sin2 = std::pow(outside_ior / film_ior, 2.0) * (1.0 - cos1 * cos1);
  if (sin2 > 1.0) return dvec3(1.0);  // total internal reflection into the film
  const double cos2 = std::sqrt(1.0 - sin2);
  const auto f0_of = [](double n2, double n1) { return std::pow((n2 - n1) / (n2 + n1), 2.0); };
  const double r12 = f0_of(film_ior, outside_ior) + (1.0 - f0_of(film_ior, outside_ior)) * schlick5(cos1);
  const double t121 = 1.0 - r12;
  const double phi21 = dpi - (film_ior < outside_ior ? dpi : 0.0);
  dvec3 r23, phi23;
  for (int c = 0; c < 3; ++c) {
    const double root = std::sqrt(std::min(base_f0[c], 0.9999));
    const double base_ior = (1.0 + root) / (1.0 - root);
    const double f0 = f0_of(base_ior, film_ior);
    r23[c] = f0 + (1.0 - f0) * schlick5(cos2);
    phi23[c] = base_ior < film_ior ? dpi : 0.0;
  }
  const double opd = 2.0 * film_ior * thickness * cos2;
  const dvec3 phi = dvec3(phi21) + phi23;
  const dvec3 r123 = glm::clamp(r12 * r23, dvec3(1e-5), dvec3(0.9999));
  const dvec3 rs = t121 * t121 * r23 / (dvec3(1.0) - r123);
  dvec3 out = r12 + rs, cm = rs - t121;
  for (int k = 1; k <= 2; ++k) {
    cm *= glm::sqrt(r123);
    out += cm * 2.0 * sensitivity(k * opd, double(k) * phi);
  }
  return glm::max(out, dvec3(0.0));
}

double reference_sheen_albedo(double cos_v, double r) {
  // ∫ D V (n·l) dω_l over the hemisphere of l, midpoint rule in (cos θ_l, φ): dω = d(cos θ) dφ.
  constexpr int cos_steps = 400, phi_steps = 200;  // φ over [0, π], doubled by symmetry
  const dvec3 v(std::sqrt(1.0 - cos_v * cos_v), 0.0, cos_v);
  double sum = 0.0;
  for (int i = 0; i < cos_steps; ++i) {
    const double ct = (i + 0.5) / cos_steps, st = std::sqrt(1.0 - ct * ct);
    for (int j = 0; j < phi_steps; ++j) {
      const double phi = (j + 0.5) * dpi / phi_steps;
      const dvec3 l(st * std::cos(phi), st * std::sin(phi), ct);
      const dvec3 h = glm::normalize(v + l);
      sum += charlie_d(r, h.z) * charlie_v(r, cos_v, ct) * ct;
    }
  }
  return sum * 2.0 * (1.0 / cos_steps) * (dpi / phi_steps);
}

dvec3 reference_brdf(const reference_material& m, const dvec3& n, const dvec3& v, const dvec3& l) {
  const double nv = glm::dot(n, v), nl = glm::dot(n, l);
  const dvec3 nc = m.clearcoat_normal == dvec3(0.0) ? n : m.clearcoat_normal;
  const double coat_weight = m.clearcoat * (0.04 + 0.96 * schlick5(glm::dot(nc, v)));
  const double sheen_strength = max3(m.sheen_color);
  const auto sheen_scaling = [&](double cos_l) {
    if (sheen_strength <= 0.0) return 1.0;
    return std::max(std::min(1.0 - sheen_strength * reference_sheen_albedo(nv, m.sheen_roughness),
                             1.0 - sheen_strength * reference_sheen_albedo(cos_l, m.sheen_roughness)),
                    0.0);
  };
  const dvec3 f0 = glm::min(std::pow((m.ior - 1.0) / (m.ior + 1.0), 2.0) * m.specular_color, dvec3(1.0));
  if (nl < 0.0) {  // the diffuse transmission, Fresnel at the view
    const dvec3 fr = m.specular * fresnel(m, f0, nv);
    const dvec3 btdf = (1.0 - max3(fr)) * m.diffuse_transmission * m.diffuse_transmission_color / dpi;
    return btdf * (1.0 - m.metallic) * sheen_scaling(-nl) * (1.0 - coat_weight);
  }
  const dvec3 h = glm::normalize(v + l);
  const double nh = glm::dot(n, h), vh = glm::dot(v, h);
  const double alpha = m.roughness * m.roughness;
  double specular = ggx(alpha, nh, nv, nl);
  if (m.anisotropy > 0.0) {
    const dvec3 t = m.anisotropy_direction, b = glm::cross(n, t);
    specular = ggx_anisotropic(glm::mix(alpha, 1.0, m.anisotropy * m.anisotropy), alpha, t, b, n, v, l, h);
  }
  // KHR_materials_specular's fresnel_mix over mix(diffuse_brdf, diffuse_btdf, diffuseTransmission).
  const dvec3 fr = m.specular * fresnel(m, f0, vh);
  const dvec3 dielectric = (1.0 - max3(fr)) * (1.0 - m.diffuse_transmission) * m.base / dpi + fr * specular;
  const dvec3 metal = fresnel(m, m.base, vh) * specular;
  dvec3 f = glm::mix(dielectric, metal, m.metallic);
  if (sheen_strength > 0.0)
    f = m.sheen_color * charlie_d(m.sheen_roughness, nh) * charlie_v(m.sheen_roughness, nv, nl) +
        f * sheen_scaling(nl);
  if (m.clearcoat > 0.0) {
    const double coat_alpha = std::max(m.clearcoat_roughness * m.clearcoat_roughness, 1e-3);
    const double cv = glm::dot(nc, v), cl = glm::dot(nc, l);
    const dvec3 coat = cv > 0.0 && cl > 0.0 ? dvec3(ggx(coat_alpha, glm::dot(nc, h), cv, cl)) : dvec3(0.0);
    f = glm::mix(f, coat, coat_weight);
  }
  return f;
}

}  // namespace kiln::testing
