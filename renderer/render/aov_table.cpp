#include "render/aov_table.h"

namespace kiln {

using S = aov_shape;
using M = aov_sampling;

const aov_row aov_table[aov_count] = {
    {aov::beauty, "beauty", "rgba", "R G B A", S::rgba, M::filtered, false, true, false,
     "R G B A, premultiplied colour"},
    {aov::depth, "Z", "depth", "Z", S::scalar, M::nearest, true, false, false,
     "ray distance, or planar depth with --depth-mode"},
    {aov::normal, "N", "N", "N.X N.Y N.Z", S::triple, M::nearest, false, true, false, "world shading normal"},
    {aov::position, "P", "P", "P.X P.Y P.Z", S::triple, M::nearest, true, false, false, "world position"},
    {aov::albedo, "albedo", "albedo", "albedo.R albedo.G albedo.B", S::triple, M::nearest, false, true, false,
     "base colour after textures and vertex colours"},
    {aov::uv, "uv", "uv", "uv.U uv.V", S::pair, M::nearest, false, false, false, "TEXCOORD_0"},
    {aov::ids, "id", "id", "id.object id.material id.instance", S::ids, M::nearest, true, false, false,
     "glTF node, material and scene instance as integers"},
    {aov::motion, "motion", "forward backward", "forward.u forward.v backward.u backward.v", S::motion,
     M::nearest, true, false, false, "screen-space motion to the next and previous frame, in pixels"},
    {aov::crypto_object, "crypto_object", "", "", S::ranks, M::ranks, true, false, false,
     "Cryptomatte of the node names"},
    {aov::crypto_material, "crypto_material", "", "", S::ranks, M::ranks, true, false, false,
     "Cryptomatte of the material names"},
    {aov::direct, "direct", "direct", "direct.R direct.G direct.B", S::triple, M::filtered, false, true,
     false, "the beauty's emission, direct light and background seen directly"},
    {aov::reflection, "reflection", "reflection", "reflection.R reflection.G reflection.B", S::triple,
     M::filtered, false, true, false, "the beauty through the first mirror ray"},
    {aov::refraction, "refraction", "refraction", "refraction.R refraction.G refraction.B", S::triple,
     M::filtered, false, true, false, "the beauty through the first refracted ray"},
    {aov::light_groups, "lightgroups", "", "", S::per_group, M::filtered, false, true, false,
     "the beauty by light: one layer per light, emission and environment"},
    {aov::albedo_filtered, "albedo_filtered", "albedo_filtered",
     "albedo_filtered.R albedo_filtered.G albedo_filtered.B", S::triple, M::filtered, false, true, true,
     "denoising albedo filtered like the beauty"},
    {aov::normal_filtered, "N_filtered", "N_filtered", "N_filtered.X N_filtered.Y N_filtered.Z", S::triple,
     M::filtered, false, true, false, "shading normal filtered like the beauty"},
    {aov::diffuse, "diffuse", "diffuse", "diffuse.R diffuse.G diffuse.B", S::triple, M::filtered, false, true,
     false, "direct light by the Lambert lobe"},
    {aov::specular, "specular", "specular", "specular.R specular.G specular.B", S::triple, M::filtered, false,
     true, false, "direct light by the glossy lobes"},
    {aov::shadow, "shadow", "", "", S::per_matte, M::filtered, false, true, true,
     "one shadow matte per light and the environment"},
    {aov::emission, "emission", "emission", "emission.R emission.G emission.B", S::triple, M::filtered, false,
     true, false, "emitted light seen directly"},
};

int beauty_part_count(const aov_set& a, int light_groups) {
  int parts = 0;
  for (const aov_row& row : aov_table) {
    if (row.sampling != aov_sampling::filtered || row.shape == aov_shape::rgba || !a.has(row.id)) continue;
    parts += row.shape == aov_shape::per_group   ? light_groups
             : row.shape == aov_shape::per_matte ? shadow_part_count(light_groups)
                                                 : 1;
  }
  return parts;
}

std::string aov_name_list() {
  std::string list;
  for (const aov_row& row : aov_table) {
    list += (list.empty() ? "" : ", ") + std::string(row.name);
    if (row.id == aov::crypto_material) list += ", cryptomatte";
  }
  return list;
}

std::string aov_help() {
  std::string help = "Comma-separated outputs to write:";
  for (const aov_row& row : aov_table)
    help += std::string(row.id == aov::beauty ? " " : ", ") + row.name + " (" + row.help + ")";
  return help + "; cryptomatte for both Cryptomatte layers (default beauty,Z,N)";
}

}  // namespace kiln
