#include "shade/path_record.h"

namespace kiln {

namespace {

float mean_component(const vec3& v) { return (v.x + v.y + v.z) / 3.0f; }

// The shadow matte's value: the share of the unshadowed luminance that is blocked.
float blocked_share(float unshadowed, float lit) { return std::clamp(1.0f - lit / unshadowed, 0.0f, 1.0f); }

}  // namespace

void camera_path::cover(uint32_t instance, float coverage) {
  if (!(coverage > 0.0f)) return;
  for (int i = 0; i < layer_count; ++i)
    if (layers[i].instance == instance) {
      layers[i].coverage += coverage;
      return;
    }
  if (layer_count == max_path_layers) {
    layers[layer_count - 1].coverage += coverage;  // deeper layers than that are folded into the last
    return;
  }
  layers[layer_count++] = {instance, coverage};
}

void camera_path::add_surface(uint32_t instance, const vec3& position, const vec3& radiance, float coverage) {
  if (!record_surfaces) return;
  if (surface_count == max_path_layers) {
    // Deeper surfaces than that fold into the last, so the colours still sum to the sample's.
    path_surface& last = surfaces[surface_count - 1];
    last.radiance += radiance;
    last.coverage += coverage;
    return;
  }
  surfaces[surface_count++] = {instance, glm::length(position - origin), radiance, coverage};
}

void record_light_passes(const path_record& r, size_t light, const brdf_lobes& lobes,
                         const vec3& unshadowed_light, const vec3& visibility) {
  if (!r.passes) return;
  camera_passes& p = *r.passes;
  record_pass(r, aov::diffuse, lobes.diffuse * unshadowed_light * visibility);
  record_pass(r, aov::specular, lobes.specular * unshadowed_light * visibility);
  if (p.shadow.empty()) return;
  const float unshadowed = luminance((lobes.diffuse + lobes.specular) * unshadowed_light);
  if (!(unshadowed > 0.0f)) return;
  const float lit = luminance((lobes.diffuse + lobes.specular) * unshadowed_light * visibility);
  p.shadow[light] += r.share * blocked_share(unshadowed, lit);
}

void record_environment_passes(const path_record& r, size_t matte, const vec3& diffuse, const vec3& specular,
                               float unshadowed, float lit) {
  if (!r.passes) return;
  record_pass(r, aov::diffuse, diffuse);
  record_pass(r, aov::specular, specular);
  if (r.passes->shadow.size() > matte && unshadowed > 0.0f)
    r.passes->shadow[matte] += r.share * blocked_share(unshadowed, lit);
}

void record_covered(const path_record& r, const surface_point& sp, const material_point& mp,
                    const vec3& radiance, float escaped_before) {
  if (!r.camera || !r.record_layers) return;
  const float covered = r.share - (r.camera->transparency - escaped_before);
  r.camera->cover(sp.instance, covered);
  // The sample's radiance is Σ share · radiance over the surfaces its path covers (BLEND and the
  // part behind scale by the same shares), so each deep surface gets its own term.
  r.camera->add_surface(sp.instance, sp.position, r.share * radiance, covered);
  // The denoiser's albedo and normal go by the surface's coverage, like its matte.
  if (r.passes && covered > 0.0f) {
    r.passes->value(aov::albedo_filtered) += covered * denoising_albedo(mp);
    if (is_finite(sp.shading_normal)) r.passes->value(aov::normal_filtered) += covered * sp.shading_normal;
  }
}

void record_untraced_behind(const path_record& r, const surface_point& sp, float share) {
  if (!r.camera || !r.record_layers) return;
  r.camera->cover(sp.instance, share);
  r.camera->add_surface(sp.instance, sp.position, vec3(0.0f), share);
}

bool record_escape(const path_record& r, float weight) {
  if (!r.camera || r.camera->background_visible) return false;
  r.camera->transparency += r.share * weight;
  return true;
}

bool record_holdout(const path_record& r) {
  if (!r.camera) return false;
  r.camera->transparency += r.share;
  return true;
}

path_record secondary_record(const path_record& r, const vec3& tint) {
  path_record next = r;
  next.camera = nullptr;
  next.split = nullptr;
  next.passes = nullptr;
  next.tint = tint;
  return next;
}

path_record refracted_record(const path_record& r, const vec3& weight) {
  path_record next = secondary_record(r, r.tint * weight);
  if (!r.camera || !r.camera->transmission_transparent) return next;
  next.camera = r.camera;
  next.share = r.share * mean_component(weight);
  next.record_layers = false;  // what glass shows bent belongs to the glass's matte; the caller
                               // files all of its light under refraction
  return next;
}

path_record scaled_record(const path_record& r, float weight) {
  path_record next = r;
  next.share = r.share * weight;
  next.tint = r.tint * weight;
  return next;
}

path_record through_volume_record(const path_record& r, const vec3& absorption) {
  path_record next = r;
  next.share = r.share * mean_component(absorption);
  next.split = nullptr;
  next.passes = nullptr;
  next.tint = r.tint * absorption;
  return next;
}

}  // namespace kiln
