#include "io/gltf/gltf_material_lobes.h"

#include "io/gltf/gltf_common.h"
#include "io/gltf/gltf_material_fields.h"

namespace kiln::gltf_internal {
namespace {

// Reads a number member in [low, high] into out when present.
void read_number(const tinygltf::Value& ext, const char* key, double low, double high, float& out,
                 const std::string& file, const std::string& at) {
  double value = 0.0;
  if (bounded_number(ext, key, low, high, value, file, at)) out = static_cast<float>(value);
}

void convert_clearcoat(const tinygltf::Model& model, const tinygltf::Value& ext, material& m,
                       texture_remap& remap, scene& out, const std::string& file, const std::string& at) {
  read_number(ext, "clearcoatFactor", 0.0, 1.0, m.clearcoat_factor, file, at);
  m.clearcoat_texture = extension_texture(model, ext, "clearcoatTexture", remap, out, file, at);
  read_number(ext, "clearcoatRoughnessFactor", 0.0, 1.0, m.clearcoat_roughness_factor, file, at);
  m.clearcoat_roughness_texture =
      extension_texture(model, ext, "clearcoatRoughnessTexture", remap, out, file, at);
  m.clearcoat_normal_texture = extension_texture(model, ext, "clearcoatNormalTexture", remap, out, file, at);
}

void convert_sheen(const tinygltf::Model& model, const tinygltf::Value& ext, material& m,
                   texture_remap& remap, scene& out, const std::string& file, const std::string& at) {
  color_member(ext, "sheenColorFactor", m.sheen_color_factor, file, at);
  m.sheen_color_texture = extension_texture(model, ext, "sheenColorTexture", remap, out, file, at);
  read_number(ext, "sheenRoughnessFactor", 0.0, 1.0, m.sheen_roughness_factor, file, at);
  m.sheen_roughness_texture = extension_texture(model, ext, "sheenRoughnessTexture", remap, out, file, at);
}

void convert_iridescence(const tinygltf::Model& model, const tinygltf::Value& ext, material& m,
                         texture_remap& remap, scene& out, const std::string& file, const std::string& at) {
  read_number(ext, "iridescenceFactor", 0.0, 1.0, m.iridescence_factor, file, at);
  m.iridescence_texture = extension_texture(model, ext, "iridescenceTexture", remap, out, file, at);
  read_number(ext, "iridescenceIor", 1.0, largest_material_value, m.iridescence_ior, file, at);
  read_number(ext, "iridescenceThicknessMinimum", 0.0, largest_material_value,
              m.iridescence_thickness_minimum, file, at);
  read_number(ext, "iridescenceThicknessMaximum", 0.0, largest_material_value,
              m.iridescence_thickness_maximum, file, at);
  m.iridescence_thickness_texture =
      extension_texture(model, ext, "iridescenceThicknessTexture", remap, out, file, at);
}

void convert_diffuse_transmission(const tinygltf::Model& model, const tinygltf::Value& ext, material& m,
                                  texture_remap& remap, scene& out, const std::string& file,
                                  const std::string& at) {
  read_number(ext, "diffuseTransmissionFactor", 0.0, 1.0, m.diffuse_transmission_factor, file, at);
  m.diffuse_transmission_texture =
      extension_texture(model, ext, "diffuseTransmissionTexture", remap, out, file, at);
  color_member(ext, "diffuseTransmissionColorFactor", m.diffuse_transmission_color_factor, file, at);
  m.diffuse_transmission_color_texture =
      extension_texture(model, ext, "diffuseTransmissionColorTexture", remap, out, file, at);
}

void convert_anisotropy(const tinygltf::Model& model, const tinygltf::Value& ext, material& m,
                        texture_remap& remap, scene& out, const std::string& file, const std::string& at) {
  read_number(ext, "anisotropyStrength", 0.0, 1.0, m.anisotropy_strength, file, at);
  read_number(ext, "anisotropyRotation", -1e6, 1e6, m.anisotropy_rotation, file, at);
  m.anisotropy_texture = extension_texture(model, ext, "anisotropyTexture", remap, out, file, at);
}

}  // namespace

void convert_material_lobes(const tinygltf::Model& model, const tinygltf::Material& src, material& m,
                            texture_remap& remap, scene& out, const std::string& file,
                            const std::string& ext_where) {
  using reader = void (*)(const tinygltf::Model&, const tinygltf::Value&, material&, texture_remap&, scene&,
                          const std::string&, const std::string&);
  const std::pair<const char*, reader> readers[] = {
      {"KHR_materials_clearcoat", convert_clearcoat},
      {"KHR_materials_sheen", convert_sheen},
      {"KHR_materials_iridescence", convert_iridescence},
      {"KHR_materials_diffuse_transmission", convert_diffuse_transmission},
      {"KHR_materials_anisotropy", convert_anisotropy}};
  for (const auto& [name, read] : readers)
    if (const tinygltf::Value* ext = find_extension(src, name)) {
      const std::string at = pointer_join(ext_where, name);
      require(ext->IsObject(), file, at, std::string(name) + " must be an object");
      read(model, *ext, m, remap, out, file, at);
    }
  if (const tinygltf::Value* ext = find_extension(src, "KHR_materials_dispersion"))
    read_number(*ext, "dispersion", 0.0, largest_material_value, m.dispersion, file,
                pointer_join(ext_where, "KHR_materials_dispersion"));
}

}  // namespace kiln::gltf_internal
