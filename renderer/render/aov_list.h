// Which arbitrary output variables (AOVs) a render produces and writes, parsed from `--aovs`.
// Depends on core only.
#pragma once

#include <algorithm>
#include <optional>
#include <string>

namespace kiln {

// What Z holds: the ray distance from the camera, or the planar depth along the view axis (the
// ray distance times the cosine between the ray and the view direction).
enum class depth_mode { distance, planar };

// The Cryptomatte specification's suggested default: 6 ranks, three RGBA channel sets.
constexpr int default_cryptomatte_depth = 6;
constexpr int max_cryptomatte_depth = 32;

// One flag per AOV. The default is what kiln has always written: beauty, Z and N.
struct aov_set {
  bool beauty = true;     // R G B A: premultiplied colour, filtered
  bool depth = true;      // Z: ray distance (or planar depth) of the nearest sample
  bool normal = true;     // N.X N.Y N.Z: world shading normal of the nearest sample
  bool position = false;  // P.X P.Y P.Z: world position of the nearest sample's hit
  bool albedo = false;    // albedo.R albedo.G albedo.B: base colour after textures and vertex colours
  bool uv = false;        // uv.U uv.V: TEXCOORD_0 of the nearest sample's hit
  bool ids = false;       // id.object id.material id.instance: glTF node, material, scene instance
  // forward.u forward.v backward.u backward.v: the screen-space motion of the nearest sample's
  // surface point to the next frame and to the previous one, in pixels, u right and v up (Nuke's
  // motion layers; render/motion_vectors.h). Never filtered; 0 for background.
  bool motion = false;
  // CryptoObject00.. and CryptoMaterial00..: Cryptomatte ranks of the glTF node and material names.
  bool crypto_object = false;
  bool crypto_material = false;
  // direct.RGB, reflection.RGB, refraction.RGB: the beauty split by first event (shade/path_record.h's
  // light_split), filtered like it; the three sum to R G B.
  bool direct = false;
  bool reflection = false;
  bool refraction = false;
  // lightgroup_<light>.RGB per punctual light (the headlight too), lightgroup_emission.RGB and
  // lightgroup_environment.RGB: the beauty by the source its light came from, through every
  // reflection and refraction, filtered like it; they sum to R G B (render/light_groups.h).
  bool light_groups = false;
  // Passes for a denoiser, folded with the beauty's own filter weights like the light split (see
  // shade/whitted.h's camera_passes): albedo_filtered.RGB (the denoising albedo of the surfaces the
  // camera sees, times their coverage) and N_filtered.XYZ (their shading normals, the same way).
  bool albedo_filtered = false;
  bool normal_filtered = false;
  // diffuse.RGB and specular.RGB: the punctual lights' direct light at the surfaces the camera sees
  // by BRDF lobe (Lambert, GGX); with emission and the background seen directly they make direct.
  bool diffuse = false;
  bool specular = false;
  // shadow_<light>.A per punctual light: the share of that light's unshadowed direct light at the
  // surfaces the camera sees that shadow rays find blocked (luminance), times coverage.
  bool shadow = false;
  // Cryptomatte ranks (id, coverage pairs) kept per pixel.
  int crypto_depth = default_cryptomatte_depth;
  // What Z holds.
  depth_mode depth_kind = depth_mode::distance;
};

// Parses a comma-separated list of names (beauty, Z, N, P, albedo, uv, id, motion, crypto_object,
// crypto_material, and cryptomatte for both, direct, reflection, refraction, lightgroups,
// albedo_filtered, N_filtered, diffuse, specular, shadow; case-sensitive,
// each at most once, at least one). Returns empty and sets *bad to the offending item otherwise.
std::optional<aov_set> parse_aov_list(const std::string& text, std::string* bad);

// True when some output needs the light split.
inline bool wants_light_split(const aov_set& a) { return a.direct || a.reflection || a.refraction; }

// True when some output needs the camera path's passes (shade/path_record.h's camera_passes).
inline bool wants_camera_passes(const aov_set& a) {
  return a.albedo_filtered || a.normal_filtered || a.diffuse || a.specular || a.shadow;
}

// The canonical comma-separated list, in channel order: "beauty,Z,N" for the default (the
// cryptomatte shorthand is listed as crypto_object,crypto_material).
std::string aov_list_name(const aov_set& aovs);

// "distance" or "planar"; empty for anything else.
std::optional<depth_mode> parse_depth_mode(const std::string& name);

}  // namespace kiln
