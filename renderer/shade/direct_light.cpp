#include "shade/direct_light.h"

#include <algorithm>
#include <cmath>

#include "core/float_bits.h"
#include "core/hash_random.h"
#include "shade/environment.h"
#include "shade/environment_light.h"
#include "shade/lights.h"
#include "shade/lobe_sampling.h"
#include "shade/shadow_transmittance.h"
#include "shade/spawn_ray.h"

namespace kiln {

namespace {

// Shadow rays stop just short of the light so that a light placed on a surface
// is not shadowed by that surface; the margin is relative, so it holds at any
// scene scale.
constexpr float shadow_length_fraction = 1.0f - 1e-4f;

// Visibility of a light along a shadow ray. Without see-through materials one occlusion query
// answers it. With them the walk that attenuates by transmission colours runs directly: its first
// closest-hit query finds nothing exactly when occluded() would say the segment is clear (the
// accelerator tests hold the two queries to agree), so a separate occluded() first would only
// repeat that query's traversal for every blocked ray.
vec3 shadow_visibility(const shading_context& ctx, const ray& shadow, ray_counts& counts) {
  if (!ctx.see_through_shadows) {
    ++counts.shadow;
    return ctx.accel.occluded(shadow) ? vec3(0.0f) : vec3(1.0f);
  }
  return shadow_transmittance(ctx.world, ctx.accel, shadow, counts.shadow);
}

// The distance a shadow ray from r's origin toward light l (sampled as ls) runs: just short of the
// light, or on forever toward a directional light.
void stop_short_of_light(const light& l, const light_sample& ls, ray& r) {
  r.tmax = std::isinf(ls.distance) ? inf : glm::length(vec3(l.position) - r.origin) * shadow_length_fraction;
}

// A light on the far side of a diffusely transmitting surface (KHR_materials_diffuse_transmission):
// its Lambert transmission, shadowed along a ray that leaves from the back of the surface.
template <typename Sink>
void plan_back_light(const surface_point& sp, const material_point& mp, const vec3& to_viewer, const light& l,
                     const light_sample& ls, light_term& term, Sink& out) {
  term.kind = light_term_kind::back;
  const float cos_theta = -glm::dot(sp.shading_normal, ls.direction);
  const vec3 f =
      cos_theta > 0.0f ? evaluate_diffuse_btdf(mp, sp.shading_normal, to_viewer, ls.direction) : vec3(0.0f);
  if (f == vec3(0.0f)) return out.take(term, nullptr);  // filed as no light, as it always was
  term.value = f * ls.irradiance * cos_theta;
  if (!l.casts_shadows) return out.take(term, nullptr);
  ray shadow = spawn_ray(sp, ls.direction, ray_kind::shadow);
  stop_short_of_light(l, ls, shadow);
  out.take(term, &shadow);
}

// The terms of every punctual light: the light it brings unshadowed and its shadow ray, handed to
// out.take(term, shadow ray or null) in the lights' order.
template <typename Sink>
void plan_punctual_light(const shading_context& ctx, const surface_point& sp, const material_point& mp,
                         const vec3& to_viewer, const light_query& q, Sink& out) {
  if (ctx.world.lights.empty()) return;
  const brdf_view view = brdf_view_of(mp, sp.shading_normal, to_viewer);
  for (size_t i = 0; i < ctx.world.lights.size(); ++i) {
    const light& l = ctx.world.lights[i];
    light_sample ls = sample_light(l, sp.position);
    if (ls.irradiance == vec3(0.0f)) continue;
    light_term term;
    term.light = uint32_t(i);
    // A light behind the surface cannot reach it, whatever the shading normal says. The surface is
    // the smooth one the vertex normals describe, not the flat facet: facets just past a low-poly
    // mesh's terminator still face the light there, and their shadow rays start on that smooth
    // surface (sp.smooth_position), above the neighbouring facets.
    if (glm::dot(sp.smooth_normal, ls.direction) <= 0.0f) {
      // ...except through a surface that transmits diffusely: then it lights the far side.
      if (!(diffuse_see_through_weight(mp) > 0.0f)) continue;
      plan_back_light(sp, mp, to_viewer, l, ls, term, out);
      continue;
    }
    float cos_theta = glm::dot(sp.shading_normal, ls.direction);
    if (cos_theta <= 0.0f) continue;
    const float scale = ctx.options.highlight_footprint_scale;
    const highlight_footprint footprint =
        highlight_footprint_of(q.cone.spread * scale, q.cone.width * scale, ls.distance, sp.curvature);
    vec3 f = evaluate_brdf(view, mp, sp.shading_normal, to_viewer, ls.direction, footprint);
    if (f == vec3(0.0f)) continue;
    // The passes' lobes are evaluated beside f, which stays the beauty's (its bytes do not change).
    if (q.passes)
      term.lobes = evaluate_brdf_lobes(view, mp, sp.shading_normal, to_viewer, ls.direction, footprint);
    term.incident = ls.irradiance * cos_theta;
    term.value = f * ls.irradiance * cos_theta;
    if (!l.casts_shadows) {
      out.take(term, nullptr);
      continue;
    }
    ray shadow = spawn_shadow_ray_above(sp, ls.direction);
    stop_short_of_light(l, ls, shadow);
    out.take(term, &shadow);
  }
}

// Veach's power heuristic (β = 2) for a sample drawn with density pdf against another strategy's
// other, in the form that cannot overflow.
float power_heuristic(float pdf, float other) {
  if (!(pdf > 0.0f)) return 0.0f;
  const float ratio = other / pdf;
  return 1.0f / (1.0f + ratio * ratio);
}

// The term of the environment's light arriving along the unit direction l, times weight (the
// sample's MIS weight over its density), with its shadow ray: the lobes above the smooth surface,
// the diffuse transmission below it (from the back, as plan_back_light lights it).
template <typename Sink>
void plan_environment_direction(const shading_context& ctx, const surface_point& sp, const material_point& mp,
                                const vec3& to_viewer, const brdf_view& view, const glossy_weights& glossy,
                                const vec3& l, const vec2& uv, float weight, Sink& out) {
  const bool above = glm::dot(sp.smooth_normal, l) > 0.0f;
  const float cos_theta = above ? glm::dot(sp.shading_normal, l) : -glm::dot(sp.shading_normal, l);
  if (!(cos_theta > 0.0f) || !(weight > 0.0f)) return;
  light_term term;
  term.kind = light_term_kind::environment;
  if (above)
    term.lobes = evaluate_brdf_lobes(view, mp, sp.shading_normal, to_viewer, l, glossy);
  else if (diffuse_see_through_weight(mp) > 0.0f)
    term.lobes.diffuse = evaluate_diffuse_btdf(mp, sp.shading_normal, to_viewer, l);
  if (term.lobes.diffuse == vec3(0.0f) && term.lobes.specular == vec3(0.0f)) return;
  term.incident = environment_radiance_at(ctx.world, uv) * (cos_theta * weight);
  if (term.incident == vec3(0.0f)) return;
  const ray shadow = above ? spawn_shadow_ray_above(sp, l) : spawn_ray(sp, l, ray_kind::shadow);
  out.take(term, &shadow);
}

// The random numbers of pair i of n: light_u draws from the map, lobe_u from the material's lobes
// (its first number picks the lobe). The pairs are stratified over the map's rows and over the
// choice of lobe.
void environment_pair_numbers(const light_query& q, int i, int n, vec2& light_u, vec3& lobe_u) {
  const auto next = [&q, i](uint32_t dimension) { return hash_to_unit(q.seed, uint32_t(i), dimension); };
  const float stratum = float(i);
  light_u = vec2(next(1), std::min((stratum + next(2)) / float(n), 0.99999994f));
  vec2 lobe(next(4), next(5));
  if (q.stratum.count > 0) {
    // The camera's first surface: its pixel's samples × n pairs take consecutive points of a
    // scrambled (0, 2)-sequence, so the pixel's estimate is stratified over both domains.
    const uint32_t point = q.stratum.index * uint32_t(n) + uint32_t(i), key = q.stratum.scramble;
    sobol_2d(point, hash_u32(key ^ 0x1B56C4E9U), hash_u32(key ^ 0x27D4EB2FU), light_u.x, light_u.y);
    sobol_2d(point, hash_u32(key ^ 0x165667B1U), hash_u32(key ^ 0x61C88647U), lobe.x, lobe.y);
  }
  lobe_u = vec3(std::min((stratum + next(3)) / float(n), 0.99999994f), lobe.x, lobe.y);
}

// A direction drawn from a material's lobes, with its density and its map coordinates (found once,
// for the map's density and its radiance); pdf 0 when none was drawn.
struct lobe_direction {
  vec3 direction{0.0f};
  float pdf = 0.0f;
  vec2 uv{0.0f};
};

lobe_direction lobe_direction_of(const environment_light& e, const lobe_sampler& lobes, const vec3& to_viewer,
                                 const vec3& u) {
  lobe_direction out;
  const std::optional<vec3> l = sample_lobes(lobes, to_viewer, u);
  if (!l) return out;
  const float pdf = lobe_pdf(lobes, to_viewer, *l);
  if (!(pdf > 0.0f)) return out;
  out.direction = *l;
  out.pdf = pdf;
  out.uv = e.uniform ? vec2(0.0f) : environment_uv(*l, e.rotation);
  return out;
}

// The environment's terms: environment_samples pairs of samples (half as many off the camera's
// path), one drawn from the map's importance and one from the material's lobes, each weighed
// against the other's density. The pairs are stratified over the map's rows and over the choice
// of lobe. Returns the number of pairs.
template <typename Sink>
int plan_environment_light(const shading_context& ctx, const surface_point& sp, const material_point& mp,
                           const vec3& to_viewer, const light_query& q, Sink& out) {
  const environment_light& e = *ctx.environment;
  const glossy_weights glossy = environment_glossy_weights(ctx.options, mp);
  const lobe_sampler lobes = make_lobe_sampler(mp, sp.shading_normal, to_viewer, glossy);
  const brdf_view view = brdf_view_of(mp, sp.shading_normal, to_viewer);
  // Surfaces seen in mirrors and through glass take half as many: their light reaches the camera
  // weighted down by Fresnel and transmission, and there are as many of them as camera surfaces in
  // a scene of glass and chrome.
  const int asked = std::max(ctx.options.environment_samples, 1);
  const int n = q.camera ? asked : (asked + 1) / 2;
  // Up to `run` pairs at a time: first every direction (the map's draws made together, the lobes'
  // drawn and their map coordinates found, the map's texels for them asked for), then each pair's
  // two terms in turn. The reads of the map and its tables then overlap instead of waiting one
  // after another.
  constexpr int run = 8;
  for (int first = 0; first < n; first += run) {
    const int count = std::min(run, n - first);
    vec2 light_u[run];
    vec3 lobe_u[run];
    for (int k = 0; k < count; ++k) environment_pair_numbers(q, first + k, n, light_u[k], lobe_u[k]);
    environment_sample drawn[run];
    sample_environment_run(e, light_u, count, drawn);
    lobe_direction from_lobes[run];
    for (int k = 0; k < count; ++k) {
      from_lobes[k] = lobe_direction_of(e, lobes, to_viewer, lobe_u[k]);
      if (drawn[k].pdf > 0.0f) prefetch_environment_radiance(ctx.world, drawn[k].uv);
      if (from_lobes[k].pdf > 0.0f) prefetch_environment_radiance(ctx.world, from_lobes[k].uv);
    }
    for (int k = 0; k < count; ++k) {
      const environment_sample& es = drawn[k];
      if (es.pdf > 0.0f) {
        const float weight = power_heuristic(es.pdf, lobe_pdf(lobes, to_viewer, es.direction)) / es.pdf;
        plan_environment_direction(ctx, sp, mp, to_viewer, view, glossy, es.direction, es.uv, weight, out);
      }
      const lobe_direction& l = from_lobes[k];
      if (l.pdf > 0.0f) {
        const float weight = power_heuristic(l.pdf, environment_pdf_at(e, l.direction, l.uv)) / l.pdf;
        plan_environment_direction(ctx, sp, mp, to_viewer, view, glossy, l.direction, l.uv, weight, out);
      }
    }
  }
  return n;
}

// What the environment's terms at one shading point gather: the light by lobe, and the luminance
// arriving before and after the shadow rays (for the shadow matte).
struct environment_tally {
  vec3 diffuse{0.0f};
  vec3 specular{0.0f};
  float unshadowed = 0.0f;
  float lit = 0.0f;
};

void add_environment_term(const light_term& term, const vec3& visibility, environment_tally& tally) {
  const brdf_lobes& f = term.lobes;
  const vec3& arriving = term.incident;
  tally.diffuse += f.diffuse * arriving * visibility;
  tally.specular += f.specular * arriving * visibility;
  const vec3 unshadowed = (f.diffuse + f.specular) * arriving;
  tally.unshadowed += luminance(unshadowed);
  tally.lit += luminance(unshadowed * visibility);
}

// A point's answered terms summed, in the order they were planned.
struct light_sum {
  vec3 total{0.0f};
  environment_tally tally;
};

// Adds one answered term: a light's share is filed in its group (times the ray's tint) and, on
// the camera's path with passes, by lobe and as its shadow matte; the environment's directions are
// tallied and filed once by finish_light_sum.
void add_term(const path_record& record, const light_term& term, const vec3& visibility, light_sum& sum) {
  if (term.kind == light_term_kind::environment) return add_environment_term(term, visibility, sum.tally);
  if (term.kind == light_term_kind::front) {
    record_light_passes(record, term.light, term.lobes, term.incident, visibility);
    if (visibility == vec3(0.0f)) return;
  }
  const vec3 light = term.value * visibility;
  sum.total += light;
  record_group(record, term.light, light);
  if (term.kind == light_term_kind::back) record_diffuse(record, light);
}

// The point's direct light: the lights' total and the environment's pairs averaged (none: no pairs).
vec3 finish_light_sum(const shading_context& ctx, const path_record& record, int environment_pairs,
                      const light_sum& sum) {
  if (environment_pairs == 0) return sum.total;
  const float scale = 1.0f / float(environment_pairs);
  const environment_tally& tally = sum.tally;
  const vec3 light = (tally.diffuse + tally.specular) * scale;
  record_group(record, environment_group(ctx.world), light);
  record_environment_passes(record, ctx.world.lights.size(), tally.diffuse * scale, tally.specular * scale,
                            tally.unshadowed, tally.lit);
  return sum.total + light;
}

// Where planned terms go: kept with their shadow rays, to be answered with a run's (the wave's
// camera hits)...
struct term_store {
  light_terms& out;
  void take(light_term term, const ray* shadow) {
    if (shadow) {
      out.rays.push_back(*shadow);
      term.shadowed = true;
    }
    out.terms.push_back(term);
  }
};

// ...or answered and added up at once (every other shading point: nothing is stored).
struct term_now {
  const shading_context& ctx;
  const path_record& record;
  ray_counts& counts;
  light_sum sum;
  void take(const light_term& term, const ray* shadow) {
    add_term(record, term, shadow ? shadow_visibility(ctx, *shadow, counts) : vec3(1.0f), sum);
  }
};

}  // namespace

light_query light_query_of(const path_state& s) {
  light_query q;
  q.cone = s.cone;
  q.seed = s.seed;
  q.stratum = s.stratum;
  q.camera = s.record.camera != nullptr;
  q.passes = s.record.passes != nullptr;
  return q;
}

light_terms_span plan_direct_light(const shading_context& ctx, const surface_point& sp,
                                   const material_point& mp, const vec3& to_viewer, const light_query& q,
                                   light_terms& out) {
  light_terms_span span;
  span.first_term = uint32_t(out.terms.size());
  span.first_ray = uint32_t(out.rays.size());
  term_store store{out};
  plan_punctual_light(ctx, sp, mp, to_viewer, q, store);
  if (ctx.environment && ctx.environment->lights)
    span.environment_pairs = plan_environment_light(ctx, sp, mp, to_viewer, q, store);
  span.term_count = uint32_t(out.terms.size()) - span.first_term;
  return span;
}

namespace {

// Answers t's rays one at a time.
void answer_shadow_rays(const shading_context& ctx, light_terms& t, ray_counts& counts) {
  t.visibility.resize(t.rays.size());
  for (size_t i = 0; i < t.rays.size(); ++i) t.visibility[i] = shadow_visibility(ctx, t.rays[i], counts);
}

// Asks the rays of t.open_rays as an occlusion batch seeing `sees`, into t.blocked.
void ask_open_rays(const shading_context& ctx, light_terms& t, ray_sees sees, ray_counts& counts) {
  for (ray& r : t.open_rays) r.sees = sees;
  t.blocked.resize(t.open_rays.size());
  ctx.accel.occluded_batch(t.open_rays.data(), t.open_rays.size(), t.blocked.data());
  counts.shadow += t.open_rays.size();
}

// Keeps in t.open_rays only the rays t.blocked says were blocked (or, keep_blocked false, clear),
// each with its index in t.rays.
void keep_open_rays(light_terms& t, bool keep_blocked) {
  size_t kept = 0;
  for (size_t i = 0; i < t.open_rays.size(); ++i) {
    if (bool(t.blocked[i]) != keep_blocked) continue;
    t.open_rays[kept] = t.open_rays[i];
    t.open_index[kept++] = t.open_index[i];
  }
  t.open_rays.resize(kept);
  t.open_index.resize(kept);
}

}  // namespace

void answer_shadow_rays_together(const shading_context& ctx, light_terms& t, ray_counts& counts) {
  if (!ctx.shadow_packets) {
    answer_shadow_rays(ctx, t, counts);
    return;
  }
  const size_t n = t.rays.size();
  t.visibility.assign(n, vec3(0.0f));
  t.open_rays.assign(t.rays.begin(), t.rays.end());
  t.open_index.resize(n);
  for (size_t i = 0; i < n; ++i) t.open_index[i] = uint32_t(i);
  if (!ctx.see_through_shadows) {
    ask_open_rays(ctx, t, ray_sees::everything, counts);
    for (size_t i = 0; i < n; ++i) t.visibility[i] = t.blocked[i] ? vec3(0.0f) : vec3(1.0f);
    return;
  }
  // Whatever stops light on the segment leaves it dark, however much glass lies before it; a
  // segment clear of it and of see-through surfaces is lit in full. Only the rest is walked (an
  // occlusion query is cheaper than the walk's closest hit, and a batch cheaper than one at a time).
  ask_open_rays(ctx, t, ray_sees::light_stoppers, counts);
  keep_open_rays(t, false);
  ask_open_rays(ctx, t, ray_sees::see_through_only, counts);
  for (size_t i = 0; i < t.open_rays.size(); ++i)
    if (!t.blocked[i]) t.visibility[t.open_index[i]] = vec3(1.0f);
  keep_open_rays(t, true);
  for (size_t i = 0; i < t.open_rays.size(); ++i)
    t.visibility[t.open_index[i]] = shadow_transmittance(ctx.world, ctx.accel, t.open_rays[i], counts.shadow);
}

vec3 resolve_direct_light(const shading_context& ctx, const light_terms& t, const light_terms_span& span,
                          const path_state& s) {
  light_sum sum;
  size_t next_ray = span.first_ray;
  for (size_t k = span.first_term; k < span.first_term + span.term_count; ++k) {
    const light_term& term = t.terms[k];
    add_term(s.record, term, term.shadowed ? t.visibility[next_ray++] : vec3(1.0f), sum);
  }
  return finish_light_sum(ctx, s.record, span.environment_pairs, sum);
}

glossy_weights environment_glossy_weights(const shading_options& options, const material_point& mp) {
  const float limit = options.mirror_roughness_limit;
  const float base = limit > 0.0f ? std::min(mp.roughness / limit, 1.0f) : 1.0f;
  const float coat = limit > 0.0f ? std::min(layers_of(mp).clearcoat_roughness / limit, 1.0f) : 1.0f;
  return {(1.0f - mp.transmission) * base, base, coat};
}

vec3 direct_light(const shading_context& ctx, const surface_point& sp, const material_point& mp,
                  const vec3& to_viewer, const path_state& s, ray_counts& counts) {
  if (s.planned) return resolve_direct_light(ctx, *s.planned->terms, s.planned->span, s);
  const light_query q = light_query_of(s);
  term_now now{ctx, s.record, counts, {}};
  plan_punctual_light(ctx, sp, mp, to_viewer, q, now);
  const int pairs =
      ctx.environment && ctx.environment->lights ? plan_environment_light(ctx, sp, mp, to_viewer, q, now) : 0;
  return finish_light_sum(ctx, s.record, pairs, now.sum);
}

}  // namespace kiln
