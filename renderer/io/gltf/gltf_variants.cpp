#include "io/gltf/gltf_variants.h"

#include <cstdlib>

#include "core/error.h"
#include "core/message_text.h"
#include "io/gltf/gltf_common.h"

namespace kiln::gltf_internal {

namespace {

const std::string root_pointer = std::string("/extensions/") + variants_extension + "/variants";

// The extension object of an extensions map, or null.
const tinygltf::Value* extension_of(const tinygltf::ExtensionMap& extensions) {
  auto found = extensions.find(variants_extension);
  return found == extensions.end() ? nullptr : &found->second;
}

// "0 'midnight', 1 'beach'": the variants as a message lists them.
std::string listed(const std::vector<std::string>& names) {
  std::string text;
  for (size_t i = 0; i < names.size(); ++i)
    text += (i ? ", " : "") + std::to_string(i) + " " + quoted(names[i]);
  return text;
}

// The index of the variant `which` names: its name first, else an index in range; -1 if neither.
int variant_index(const std::vector<std::string>& names, const std::string& which) {
  for (size_t i = 0; i < names.size(); ++i)
    if (names[i] == which) return int(i);
  char* end = nullptr;
  const long index = std::strtol(which.c_str(), &end, 10);
  if (!which.empty() && end && *end == '\0' && index >= 0 && size_t(index) < names.size()) return int(index);
  return -1;
}

int integer_at(const tinygltf::Value& value, const std::string& file, const std::string& where) {
  if (!value.IsNumber() || !value.IsInt()) throw input_error(file, where, "expected an integer index");
  return value.GetNumberAsInt();
}

// The material a primitive's mappings give `variant` (-1: none of them lists it), checking every
// mapping on the way.
int mapped_material(const tinygltf::Value& extension, int variant, size_t variant_count,
                    size_t material_count, const std::string& file, const std::string& where) {
  const tinygltf::Value& mappings = extension.Get("mappings");
  if (!mappings.IsArray()) throw input_error(file, where + "/mappings", "expected an array of mappings");
  int chosen = -1;
  for (size_t m = 0; m < mappings.ArrayLen(); ++m) {
    const std::string at = where + "/mappings/" + std::to_string(m);
    const tinygltf::Value& mapping = mappings.Get(int(m));
    const int material = integer_at(mapping.Get("material"), file, at + "/material");
    if (material < 0 || size_t(material) >= material_count)
      throw input_error(file, at + "/material",
                        "material " + std::to_string(material) + " does not exist (file has " +
                            std::to_string(material_count) + " materials)");
    const tinygltf::Value& variants = mapping.Get("variants");
    if (!variants.IsArray() || variants.ArrayLen() == 0)
      throw input_error(file, at + "/variants", "expected a non-empty array of variant indices");
    for (size_t v = 0; v < variants.ArrayLen(); ++v) {
      const int index = integer_at(variants.Get(int(v)), file, at + "/variants/" + std::to_string(v));
      if (index < 0 || size_t(index) >= variant_count)
        throw input_error(file, at + "/variants/" + std::to_string(v),
                          "variant " + std::to_string(index) + " does not exist (file has " +
                              std::to_string(variant_count) + " variants)");
      if (index == variant && chosen < 0) chosen = material;
    }
  }
  return chosen;
}

}  // namespace

std::vector<std::string> material_variant_names(const tinygltf::Model& model, const std::string& file) {
  const tinygltf::Value* extension = extension_of(model.extensions);
  if (!extension) return {};
  const tinygltf::Value& variants = extension->Get("variants");
  if (!variants.IsArray()) throw input_error(file, root_pointer, "expected an array of variants");
  std::vector<std::string> names;
  for (size_t i = 0; i < variants.ArrayLen(); ++i) {
    const tinygltf::Value& name = variants.Get(int(i)).Get("name");
    if (!name.IsString())
      throw input_error(file, root_pointer + "/" + std::to_string(i) + "/name",
                        "a variant needs a string name");
    names.push_back(name.Get<std::string>());
  }
  return names;
}

void apply_material_variant(tinygltf::Model& model, const std::string& which, const std::string& file) {
  const std::vector<std::string> names = material_variant_names(model, file);
  int variant = -1;
  if (!which.empty()) {
    if (names.empty())
      throw input_error(file, "--variant", "the file has no KHR_materials_variants variants");
    variant = variant_index(names, which);
    if (variant < 0)
      throw input_error(file, "--variant",
                        "no variant " + quoted(which) + " (variants: " + listed(names) + ")");
  }
  for (size_t m = 0; m < model.meshes.size(); ++m)
    for (size_t p = 0; p < model.meshes[m].primitives.size(); ++p) {
      tinygltf::Primitive& prim = model.meshes[m].primitives[p];
      const tinygltf::Value* extension = extension_of(prim.extensions);
      if (!extension) continue;
      const std::string where = "/meshes/" + std::to_string(m) + "/primitives/" + std::to_string(p) +
                                "/extensions/" + variants_extension;
      const int material =
          mapped_material(*extension, variant, names.size(), model.materials.size(), file, where);
      if (material >= 0) prim.material = material;
    }
}

}  // namespace kiln::gltf_internal
