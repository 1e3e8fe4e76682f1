// The backend-neutral scene: plain data holding only what the render needs.
// Loaders fill it, accelerators and shading read it. Depends on core only: no glTF, no Embree.
// A mesh is stored once however many instances place it; attributes a material does not use
// are never stored.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/math.h"
#include "core/ray.h"

namespace kiln {

// Decoded texture image. 8-bit sources stay 8-bit (4 channels, RGBA) and are decoded per lookup;
// deeper sources are stored as float. Colour-space decoding depends on how a texture is used
// (sRGB for base colour and emissive), so it is not a property of the image.
struct image {
  std::string name;
  int width = 0;
  int height = 0;
  std::vector<uint8_t> texels8;  // width*height*4, row 0 at the top (glTF's UV origin)
  std::vector<float> texels32;   // used instead of texels8 for 16-bit or float sources
};

// Which texel buffer an image holds (its allocation, size and format): what is built from an image
// (texture pyramids, environment tables) is kept while the image it fits holds the same buffer,
// moved from one scene to the next rather than decoded again.
struct texel_buffer {
  const void* texels = nullptr;
  size_t count = 0;
  int width = 0;
  int height = 0;
  bool operator==(const texel_buffer& o) const {
    return texels == o.texels && count == o.count && width == o.width && height == o.height;
  }
};
inline texel_buffer texel_buffer_of(const image& img) {
  const bool wide = !img.texels32.empty();
  return {wide ? static_cast<const void*>(img.texels32.data()) : img.texels8.data(),
          wide ? img.texels32.size() : img.texels8.size(), img.width, img.height};
}

enum class wrap_mode { repeat, clamp_to_edge, mirrored_repeat };
enum class filter_mode { nearest, linear };
// How minification moves between mip levels: none (level 0 only), the nearest level, or a blend of
// the two nearest levels.
enum class mip_mode { none, nearest, linear };

// glTF sampler: wrap per axis, magnification filter, and the minification filter split into its
// texel filter and its mip mode (glTF's minFilter absent means LINEAR_MIPMAP_LINEAR here).
struct sampler {
  wrap_mode wrap_s = wrap_mode::repeat;
  wrap_mode wrap_t = wrap_mode::repeat;
  filter_mode filter = filter_mode::linear;  // magFilter
  filter_mode min_filter = filter_mode::linear;
  mip_mode mipmap = mip_mode::linear;
};

struct texture {
  uint32_t image = 0;
  sampler sampling;
};

// A material's use of a texture: which texture, which UV set, and a scale (the normal texture's
// scale). texture < 0 means none.
struct texture_ref {
  int32_t texture = -1;
  uint32_t texcoord = 0;  // TEXCOORD_n set (after KHR_texture_transform's texCoord override)
  float scale = 1.0f;
  // KHR_texture_transform: uv' = offset + rotate(rotation) · (uv_scale ⊙ uv).
  vec2 offset{0.0f};
  float rotation = 0.0f;  // radians, counter-clockwise as the extension defines
  vec2 uv_scale{1.0f};

  bool present() const { return texture >= 0; }
};

enum class alpha_mode { opaque, mask, blend };

// glTF metallic-roughness material with the extensions kiln understands. All colours are linear.
struct material {
  std::string name;
  // Its index in the glTF file's materials (the id.material AOV); the default material, which the
  // file does not list, takes the index one past the file's last material.
  int32_t source_index = 0;
  vec4 base_color_factor{1.0f};
  texture_ref base_color_texture;  // sRGB
  float metallic_factor = 1.0f;
  float roughness_factor = 1.0f;
  texture_ref metallic_roughness_texture;  // linear: G = roughness, B = metallic
  vec3 emissive_factor{0.0f};
  float emissive_strength = 1.0f;  // KHR_materials_emissive_strength
  texture_ref emissive_texture;    // sRGB
  texture_ref normal_texture;
  float specular_factor = 1.0f;        // KHR_materials_specular
  vec3 specular_color_factor{1.0f};    // KHR_materials_specular
  texture_ref specular_texture;        // linear: A multiplies specular_factor
  texture_ref specular_color_texture;  // sRGB: RGB multiplies specular_color_factor
  float ior = 1.5f;                    // KHR_materials_ior
  alpha_mode alpha = alpha_mode::opaque;
  float alpha_cutoff = 0.5f;
  bool double_sided = false;
  // KHR_materials_transmission: share of the dielectric part that lets light through (R channel
  // of the texture), tinted by the base colour.
  float transmission_factor = 0.0f;
  texture_ref transmission_texture;
  // KHR_materials_volume: thickness 0 means thin-walled (rays pass straight through); otherwise the
  // mesh bounds a volume that refracts and absorbs by Beer-Lambert. Thickness is in object units.
  float thickness_factor = 0.0f;
  float attenuation_distance = inf;  // world units; infinite: no absorption
  vec3 attenuation_color{1.0f};      // colour that white light has after attenuation_distance

  // KHR_materials_dispersion: the ior spreads over wavelength with Abbe number 20 / dispersion
  // (0: none); refraction then bends each of R, G and B by its own ior.
  float dispersion = 0.0f;

  // KHR_materials_clearcoat: a smooth dielectric coat (ior 1.5) over the whole material, weighted by
  // clearcoat · Fresnel(coat normal · view).
  float clearcoat_factor = 0.0f;
  texture_ref clearcoat_texture;  // linear: R multiplies clearcoat_factor
  float clearcoat_roughness_factor = 0.0f;
  texture_ref clearcoat_roughness_texture;  // linear: G multiplies clearcoat_roughness_factor
  texture_ref clearcoat_normal_texture;     // the coat's own normal map; none: the unmapped normal

  // KHR_materials_sheen: Charlie sheen over the base, which is scaled by the sheen's albedo.
  vec3 sheen_color_factor{0.0f};
  texture_ref sheen_color_texture;  // sRGB: RGB multiplies sheen_color_factor
  float sheen_roughness_factor = 0.0f;
  texture_ref sheen_roughness_texture;  // linear: A multiplies sheen_roughness_factor

  // KHR_materials_iridescence: a thin film (thickness in nanometres) over the base, whose
  // interference replaces Schlick's Fresnel by a share `iridescence`.
  float iridescence_factor = 0.0f;
  texture_ref iridescence_texture;  // linear: R multiplies iridescence_factor
  float iridescence_ior = 1.3f;
  float iridescence_thickness_minimum = 100.0f;
  float iridescence_thickness_maximum = 400.0f;
  texture_ref iridescence_thickness_texture;  // linear: G mixes minimum (0) to maximum (1)

  // KHR_materials_diffuse_transmission: the share of the diffuse lobe that passes light through the
  // surface to the other side, tinted.
  float diffuse_transmission_factor = 0.0f;
  texture_ref diffuse_transmission_texture;  // linear: A multiplies the factor
  vec3 diffuse_transmission_color_factor{1.0f};
  texture_ref diffuse_transmission_color_texture;  // sRGB: RGB multiplies the colour factor

  // KHR_materials_anisotropy: the GGX lobe stretched along a direction in the tangent plane.
  float anisotropy_strength = 0.0f;
  float anisotropy_rotation = 0.0f;  // radians, counter-clockwise from the tangent
  texture_ref anisotropy_texture;    // linear: RG direction in [-1, 1]², B multiplies the strength

  bool unlit = false;  // KHR_materials_unlit: radiance = base colour, no lighting

  bool has_volume() const { return thickness_factor > 0.0f; }
  // Whether any lobe extension (clearcoat, sheen, iridescence, diffuse transmission, anisotropy)
  // is on: only then does shading evaluate their layers.
  bool has_lobe_extensions() const {
    return clearcoat_factor > 0.0f || sheen_color_factor != vec3(0.0f) || iridescence_factor > 0.0f ||
           diffuse_transmission_factor > 0.0f || anisotropy_strength > 0.0f;
  }
};

// One unique glTF mesh primitive, as triangles, in its own object space. Stored once.
struct mesh {
  std::string name;
  std::vector<vec3> positions;
  std::vector<uint32_t> indices;  // three per triangle, counter-clockwise front faces
  std::vector<vec3> normals;      // per vertex; empty: flat (geometric) normals, as glTF says
  std::vector<vec2> texcoords0;   // empty unless a material samples TEXCOORD_0
  std::vector<vec2> texcoords1;   // empty unless a material samples TEXCOORD_1
  std::vector<vec4> colors0;      // COLOR_0 as linear RGBA (alpha 1 for vec3); empty when absent
  std::vector<vec4> tangents;     // xyz + handedness w; only when a material has a normal texture
  bounds3 bounds;                 // object space

  size_t triangle_count() const { return indices.size() / 3; }
};

// The analytic primitive kinds (see docs/quadrics.md for each canonical object space).
enum class quadric_kind {
  sphere,                  // x²+y²+z² = r²
  cylinder,                // x²+y² = r², zmin ≤ z ≤ zmax
  cone,                    // radius r at z = 0, apex at z = height, zmin ≤ z ≤ zmax
  paraboloid,              // x²+y² = r²·z/zmax, zmin ≤ z ≤ zmax
  hyperboloid_one_sheet,   // (x²+y²)/r² − z²/c² = 1, zmin ≤ z ≤ zmax
  hyperboloid_two_sheets,  // z²/c² − (x²+y²)/r² = 1, zmin ≤ z ≤ zmax
  disk,                    // z = 0, inner_radius ≤ ρ ≤ r
  general,                 // ten coefficients, clipped to box
  torus,                   // (|p|² + R² − r²)² = 4R²(x²+y²), R = major_radius, r = radius
};

// One analytic primitive definition in its own canonical object space (z is the axis). Any number
// of instances share it. Only the fields of its kind are meaningful; the loader checks them.
struct quadric {
  std::string name;
  quadric_kind kind = quadric_kind::sphere;
  double radius = 1.0;             // sphere, cylinder, cone (base), paraboloid (at zmax), hyperboloid
                                   // (waist / a), disk (outer), torus (minor)
  double inner_radius = 0.0;       // disk
  double major_radius = 0.0;       // torus
  double height = 1.0;             // cone apex height
  double c = 1.0;                  // hyperboloids: the z semi-axis
  double zmin = -1.0, zmax = 1.0;  // clipping along z for the axial kinds
  bool caps = false;               // close the axial kinds with disks at zmin/zmax where they have area
  // general: A x² + B y² + C z² + D xy + E xz + F yz + G x + H y + I z + J = 0, clipped to box.
  double coefficients[10] = {};
  bounds3 box;
  bounds3 bounds;  // tight object-space bounds, filled by geometry/quadric_bounds()
};

enum class shape_kind { mesh, quadric };

// One placement of a shape in the world. A thousand instances of one mesh cost a thousand of
// these, not a thousand meshes.
// How a render layer treats the instances outside it (--holdout, --only, --others):
// - matte: to the camera the instance cuts alpha to zero and hides what lies behind it; it still
//   casts shadows and shows in mirrors and through glass (flat layers that add up with `plus`);
// - invisible (--holdout-invisible): a matte seen by nothing but the camera's own path;
// - unseen (--others invisible): the camera's own rays pass it by as if it were not there, every
//   other ray sees it (shadows, reflections, refraction), so the layer holds its own objects whole
//   and a deep merge by depth does the holdout.
enum class holdout_kind : uint8_t { none, matte, invisible, unseen };

// Whether the camera's path meets the instance as a matte (its share of the sample transparent).
inline bool is_matte(holdout_kind k) { return k == holdout_kind::matte || k == holdout_kind::invisible; }

// Whether rays of the camera's own path (core/ray.h's ray_kind::camera) can hit the instance: every
// backend skips an unseen one for them, as if it were not in the scene.
inline bool camera_rays_hit(holdout_kind k) { return k != holdout_kind::unseen; }

// Whether a material lets a shadow ray's light through (transmission, or alphaMode BLEND's uncovered
// share): the shadow walk (shade/shadow_transmittance.h) goes on past such a surface.
inline bool lets_light_through(const material& m) {
  return !(m.transmission_factor <= 0.0f) || m.alpha == alpha_mode::blend;
}

struct instance {
  shape_kind kind = shape_kind::mesh;
  holdout_kind holdout = holdout_kind::none;
  uint32_t shape = 0;     // index into scene.meshes (or scene.quadrics for shape_kind::quadric)
  uint32_t material = 0;  // index into scene.materials
  uint32_t node = 0;      // glTF node that placed it (for ids and messages)
  dmat4 world_from_object{1.0};
  dmat4 object_from_world{1.0};
  dmat3 world_from_object_normal{1.0};  // inverse transpose of the linear part
  // Derived from world_from_object by finish_instance_transform, once rather than per hit:
  dmat3 abs_linear{1.0};    // |linear part|, elementwise: carries error bounds to world space
  bool mirrored = false;    // the linear part's determinant is negative (flips handedness)
  double mean_scale = 1.0;  // cube root of |determinant|: a length's world scale (exact if uniform)
};

enum class light_kind { point, spot, directional };

// KHR_lights_punctual light, already placed in the world. Units are glTF's: candela for point and
// spot lights, lux for directional lights.
struct light {
  std::string name;
  light_kind kind = light_kind::point;
  vec3 color{1.0f};
  float intensity = 1.0f;
  float range = 0.0f;        // 0 means infinite
  dvec3 position{0.0};       // world space (point, spot)
  vec3 direction{0, 0, -1};  // world space, the way light travels (spot, directional)
  float inner_cone_angle = 0.0f;
  float outer_cone_angle = pi / 4.0f;
  // glTF lights cast shadows. kiln's default headlight does not: a point seen from the camera is
  // always visible from a light at the camera, except through what the camera ray itself passed
  // (culled back faces, BLEND surfaces), which would only darken what the camera sees.
  bool casts_shadows = true;
};

enum class projection { perspective, orthographic };

// A glTF camera placed in the world. The camera looks along its local -Z with +Y up.
struct camera {
  std::string name;
  projection kind = projection::perspective;
  float yfov = 0.8f;          // radians (perspective)
  float aspect_ratio = 0.0f;  // 0: use the image aspect
  float xmag = 1.0f;          // half-width of the view (orthographic)
  float ymag = 1.0f;          // half-height of the view (orthographic)
  float znear = 0.0f;
  dmat4 world_from_camera{1.0};
};

// What rays that leave the scene see: a constant colour (linear RGB radiance), or an
// equirectangular map (an entry of scene.images, linear float radiance) times intensity.
struct environment {
  vec3 color{0.0f};
  int32_t map_image = -1;  // index into scene.images; -1: the constant colour
  float rotation = 0.0f;   // radians about +Y
  float intensity = 1.0f;

  bool has_map() const { return map_image >= 0; }
};

// Numbers the loader reports so that users see what was dropped or skipped.
struct load_statistics {
  size_t degenerate_triangles_dropped = 0;
  size_t non_triangle_primitives_skipped = 0;
  std::vector<std::string> warnings;
};

// Motion blur (--shutter): what moves while the shutter is open, at `steps` evenly spaced times
// from its opening (time 0) to its closing (time 1). Between steps transforms and vertices are
// interpolated linearly, as Embree interpolates them (scene/shutter_motion.h). Empty (steps 0):
// nothing moves, and every ray sees the frame's own pose.
struct shutter_motion {
  uint32_t steps = 0;
  // Per instance: its world_from_object at each step, or empty when it holds still.
  std::vector<std::vector<dmat4>> instance_steps;
  // Per mesh: its object-space positions (and normals, when it has them) at each step, or empty
  // when it does not deform during the shutter.
  std::vector<std::vector<std::vector<vec3>>> mesh_positions;
  std::vector<std::vector<std::vector<vec3>>> mesh_normals;

  bool any() const { return steps >= 2; }
};

struct scene {
  std::string source;  // file it came from
  std::vector<mesh> meshes;
  std::vector<quadric> quadrics;  // KILN_quadric definitions, each shared by its instances
  std::vector<instance> instances;
  // The glTF file's node names by node index ("" when unnamed), and each node's parent (-1 for a
  // root): the hierarchy that --only and --holdout select by (a node selects its subtree).
  std::vector<std::string> node_names;
  std::vector<int32_t> node_parents;
  std::vector<material> materials;  // never empty after loading: the last may be the default
  std::vector<texture> textures;
  std::vector<image> images;
  std::vector<light> lights;
  std::vector<camera> cameras;
  environment env;
  load_statistics stats;
  // The world position of the origin of the space the scene's instances, lights and cameras are
  // stored in: zero as loaded (world space); the camera's eye once the scene is moved into
  // camera-relative render space (render/render_space.h). Positions given to the user add it.
  dvec3 render_origin{0.0};
  shutter_motion shutter;  // what moves during the shutter; empty without --shutter
};

// Whether a shadow ray's walk goes on past the instance: its material lets light through, or it is
// an invisible holdout (which casts no shadow).
inline bool shadow_walks_through(const scene& s, const instance& inst) {
  return inst.holdout == holdout_kind::invisible || lets_light_through(s.materials[inst.material]);
}

// Whether a ray of this kind that sees `sees` can hit the instance; every backend skips the others
// as if they were not in the scene.
inline bool ray_may_hit(const scene& s, const instance& inst, ray_kind kind, ray_sees sees) {
  if (kind == ray_kind::camera && !camera_rays_hit(inst.holdout)) return false;
  if (sees == ray_sees::everything) return true;
  return shadow_walks_through(s, inst) == (sees == ray_sees::see_through_only);
}

// World-space bounds of every instance.
bounds3 world_bounds(const scene& s);

// Fills object_from_world, the normal matrix and the derived constants from world_from_object.
void finish_instance_transform(instance& inst);

}  // namespace kiln
