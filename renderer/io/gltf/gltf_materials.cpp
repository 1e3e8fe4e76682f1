#include "io/gltf/gltf_materials.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.h"
#include "core/format_number.h"
#include "core/message_text.h"
#include "io/gltf/gltf_common.h"
#include "io/gltf/gltf_images.h"
#include "io/gltf/gltf_material_fields.h"
#include "io/gltf/gltf_material_lobes.h"

namespace kiln::gltf_internal {
namespace {

// The KHR_texture_transform object of a textureInfo's extensions, or null.
const tinygltf::Value* transform_of(const tinygltf::ExtensionMap& extensions) {
  auto it = extensions.find("KHR_texture_transform");
  return it == extensions.end() ? nullptr : &it->second;
}

const tinygltf::Value* transform_of(const tinygltf::Value& info) {
  if (!info.IsObject() || !info.Has("extensions")) return nullptr;
  const tinygltf::Value& extensions = info.Get("extensions");
  if (!extensions.IsObject() || !extensions.Has("KHR_texture_transform")) return nullptr;
  return &extensions.Get("KHR_texture_transform");
}

// The UV set a textureInfo reads: KHR_texture_transform's texCoord overrides the textureInfo's.
int effective_texcoord(const tinygltf::Value* transform, int texcoord) {
  if (transform && transform->IsObject() && transform->Has("texCoord") && transform->Get("texCoord").IsInt())
    return transform->Get("texCoord").GetNumberAsInt();
  return texcoord;
}

// The textureInfo at key inside a material extension, as (index, texCoord); (-1, 0) when absent or
// malformed (convert_material reports malformed ones).
std::pair<int, int> extension_texture_slot(const tinygltf::Material& m, const char* extension,
                                           const char* key) {
  auto it = m.extensions.find(extension);
  if (it == m.extensions.end() || !it->second.IsObject() || !it->second.Has(key)) return {-1, 0};
  const tinygltf::Value& info = it->second.Get(key);
  if (!info.IsObject() || !info.Has("index") || !info.Get("index").IsInt()) return {-1, 0};
  const bool has_texcoord = info.Has("texCoord") && info.Get("texCoord").IsInt();
  return {info.Get("index").GetNumberAsInt(),
          effective_texcoord(transform_of(info), has_texcoord ? info.Get("texCoord").GetNumberAsInt() : 0)};
}

// The (index, texCoord) pairs of every texture slot of a material kiln reads: the glTF side of
// scene/texture_eval.h's texture_slots() (occlusion is not read).
std::vector<std::pair<int, int>> texture_slots(const tinygltf::Material& m) {
  const auto slot = [](int index, int texcoord, const tinygltf::ExtensionMap& extensions) {
    return std::pair<int, int>{index, effective_texcoord(transform_of(extensions), texcoord)};
  };
  const tinygltf::PbrMetallicRoughness& pbr = m.pbrMetallicRoughness;
  return {slot(pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord, pbr.baseColorTexture.extensions),
          slot(pbr.metallicRoughnessTexture.index, pbr.metallicRoughnessTexture.texCoord,
               pbr.metallicRoughnessTexture.extensions),
          slot(m.normalTexture.index, m.normalTexture.texCoord, m.normalTexture.extensions),
          slot(m.emissiveTexture.index, m.emissiveTexture.texCoord, m.emissiveTexture.extensions),
          extension_texture_slot(m, "KHR_materials_transmission", "transmissionTexture"),
          extension_texture_slot(m, "KHR_materials_specular", "specularTexture"),
          extension_texture_slot(m, "KHR_materials_specular", "specularColorTexture"),
          extension_texture_slot(m, "KHR_materials_clearcoat", "clearcoatTexture"),
          extension_texture_slot(m, "KHR_materials_clearcoat", "clearcoatRoughnessTexture"),
          extension_texture_slot(m, "KHR_materials_clearcoat", "clearcoatNormalTexture"),
          extension_texture_slot(m, "KHR_materials_sheen", "sheenColorTexture"),
          extension_texture_slot(m, "KHR_materials_sheen", "sheenRoughnessTexture"),
          extension_texture_slot(m, "KHR_materials_iridescence", "iridescenceTexture"),
          extension_texture_slot(m, "KHR_materials_iridescence", "iridescenceThicknessTexture"),
          extension_texture_slot(m, "KHR_materials_diffuse_transmission", "diffuseTransmissionTexture"),
          extension_texture_slot(m, "KHR_materials_diffuse_transmission", "diffuseTransmissionColorTexture"),
          extension_texture_slot(m, "KHR_materials_anisotropy", "anisotropyTexture")};
}

// glTF minFilter (OpenGL enums): NEAREST 9728, LINEAR 9729, {NEAREST,LINEAR}_MIPMAP_NEAREST 9984/9985,
// {NEAREST,LINEAR}_MIPMAP_LINEAR 9986/9987; absent (-1) keeps the sampler's trilinear default.
void set_min_filter(int gl, sampler& out) {
  if (gl < 0) return;
  out.min_filter = (gl == 9728 || gl == 9984 || gl == 9986) ? filter_mode::nearest : filter_mode::linear;
  out.mipmap = gl <= 9729 ? mip_mode::none : (gl <= 9985 ? mip_mode::nearest : mip_mode::linear);
}

wrap_mode to_wrap(int gl) {
  switch (gl) {
    case 33071:
      return wrap_mode::clamp_to_edge;
    case 33648:
      return wrap_mode::mirrored_repeat;
    default:
      return wrap_mode::repeat;  // 10497; validation refused anything else
  }
}

// The encoded bytes of a glTF image: kept by the parser for URIs, in the (validated) bufferView
// otherwise. They stay in the model, which outlives the decode.
encoded_image encoded_bytes(const tinygltf::Model& model, const tinygltf::Image& img) {
  encoded_image out;
  if (img.bufferView < 0) {
    out.data = img.image.data();
    out.size = img.image.size();
    return out;
  }
  const tinygltf::BufferView& bv = model.bufferViews[static_cast<size_t>(img.bufferView)];
  const tinygltf::Buffer& buffer = model.buffers[static_cast<size_t>(bv.buffer)];
  out.data = buffer.data.data() + bv.byteOffset;
  out.size = bv.byteLength;
  return out;
}

// Gives a glTF image its scene index on first use and queues it for decoding (decode_used_images).
int32_t resolve_image(const tinygltf::Model& model, int gltf_image, texture_remap& remap, scene& out,
                      const std::string& file) {
  int32_t& slot = remap.images[static_cast<size_t>(gltf_image)];
  if (slot >= 0) return slot;
  const tinygltf::Image& img = model.images[static_cast<size_t>(gltf_image)];
  // tinygltf only warns when an external image is missing; a broken reference is an error.
  if (img.bufferView < 0 && img.image.empty())
    throw input_error(file, pointer_join(pointer("images", gltf_image), "uri"),
                      "cannot read image file " + quoted(img.uri));
  encoded_image pending = encoded_bytes(model, img);
  pending.name = !img.name.empty() ? img.name : img.uri;
  pending.where = pointer("images", gltf_image);
  remap.pending.push_back(std::move(pending));
  out.images.emplace_back();  // filled by decode_used_images
  slot = static_cast<int32_t>(out.images.size() - 1);
  return slot;
}

// The image a texture decodes from: EXT_texture_webp's source where it has one (WebP decodes
// through the image codecs like PNG), else "source", which is also the PNG/JPEG fallback of a
// texture whose preferred source is KHR_texture_basisu. -1 when there is none.
int texture_source(const tinygltf::Model& model, const tinygltf::Texture& tex, int gltf_texture,
                   const std::string& file) {
  auto webp = tex.extensions.find("EXT_texture_webp");
  if (webp == tex.extensions.end() || !webp->second.IsObject() || !webp->second.Has("source"))
    return tex.source;
  const tinygltf::Value& v = webp->second.Get("source");
  const double index = v.IsNumber() || v.IsInt() ? v.GetNumberAsDouble() : -1.0;
  if (!(index >= 0 && index < double(model.images.size())) || index != double(int(index)))
    throw input_error(
        file,
        pointer_join(
            pointer_join(pointer_join(pointer("textures", gltf_texture), "extensions"), "EXT_texture_webp"),
            "source"),
        "needs the index of an existing image (file has " + std::to_string(model.images.size()) + ")");
  return int(index);
}

int32_t resolve_texture(const tinygltf::Model& model, int gltf_texture, texture_remap& remap, scene& out,
                        const std::string& file) {
  if (gltf_texture < 0) return -1;
  const size_t t = static_cast<size_t>(gltf_texture);
  if (remap.textures[t] >= 0) return remap.textures[t];
  const tinygltf::Texture& tex = model.textures[t];
  const int source = texture_source(model, tex, gltf_texture, file);
  if (source < 0) {
    // Only a source kiln cannot decode (KHR_texture_basisu) or none: when such an extension is
    // required, parsing already refused the file; here the texture is simply absent.
    if (!remap.missing_source_warned[t]) {
      out.stats.warnings.push_back(pointer("textures", gltf_texture) +
                                   ": texture has no source image kiln can read; it is ignored");
      remap.missing_source_warned[t] = 1;
    }
    return -1;
  }
  texture result;
  result.image = static_cast<uint32_t>(resolve_image(model, source, remap, out, file));
  if (tex.sampler >= 0) {
    const tinygltf::Sampler& s = model.samplers[static_cast<size_t>(tex.sampler)];
    result.sampling.wrap_s = to_wrap(s.wrapS);
    result.sampling.wrap_t = to_wrap(s.wrapT);
    result.sampling.filter = s.magFilter == 9728 ? filter_mode::nearest : filter_mode::linear;
    set_min_filter(s.minFilter, result.sampling);
  }
  out.textures.push_back(result);
  remap.textures[t] = static_cast<int32_t>(out.textures.size() - 1);
  return remap.textures[t];
}

texture_ref make_ref(const tinygltf::Model& model, int index, int texcoord, double scale,
                     texture_remap& remap, scene& out, const std::string& file) {
  texture_ref ref;
  ref.texture = resolve_texture(model, index, remap, out, file);
  ref.texcoord = static_cast<uint32_t>(texcoord);
  ref.scale = static_cast<float>(scale);
  return ref;
}

// Reads a vec2 member ([x, y], finite) of a KHR_texture_transform object when present.
void transform_pair(const tinygltf::Value& t, const char* key, vec2& out, const std::string& file,
                    const std::string& where) {
  if (!t.Has(key)) return;
  const tinygltf::Value& v = t.Get(key);
  const std::string at = pointer_join(where, key);
  require(v.IsArray() && v.ArrayLen() == 2, file, at, std::string(key) + " must have 2 numbers");
  for (int i = 0; i < 2; ++i) {
    require(v.Get(i).IsNumber() && std::isfinite(v.Get(i).GetNumberAsDouble()), file, at,
            std::string(key) + " must be finite numbers");
    out[i] = static_cast<float>(v.Get(i).GetNumberAsDouble());
  }
}

// KHR_texture_transform on a textureInfo (where: the textureInfo's JSON path).
void apply_texture_transform(const tinygltf::Value* t, texture_ref& ref, const std::string& file,
                             const std::string& where) {
  if (!t || !ref.present()) return;
  const std::string at = pointer_join(pointer_join(where, "extensions"), "KHR_texture_transform");
  require(t->IsObject(), file, at, "KHR_texture_transform must be an object");
  transform_pair(*t, "offset", ref.offset, file, at);
  transform_pair(*t, "scale", ref.uv_scale, file, at);
  double rotation = 0.0;
  if (bounded_number(*t, "rotation", -1e6, 1e6, rotation, file, at))
    ref.rotation = static_cast<float>(rotation);
  if (t->Has("texCoord")) {
    require(t->Get("texCoord").IsInt() && t->Get("texCoord").GetNumberAsInt() >= 0, file,
            pointer_join(at, "texCoord"), "texCoord must be a non-negative integer");
    ref.texcoord = static_cast<uint32_t>(t->Get("texCoord").GetNumberAsInt());
  }
}

}  // namespace

bool extension_number(const tinygltf::Value& object, const char* key, double& out) {
  if (!object.IsObject() || !object.Has(key)) return false;
  const tinygltf::Value& v = object.Get(key);
  if (!v.IsNumber()) return false;
  out = v.GetNumberAsDouble();
  return true;
}

const tinygltf::Value* find_extension(const tinygltf::Material& m, const char* name) {
  auto it = m.extensions.find(name);
  return it == m.extensions.end() ? nullptr : &it->second;
}

void require(bool ok, const std::string& file, const std::string& where, const std::string& reason) {
  if (!ok) throw input_error(file, where, reason);
}

bool bounded_number(const tinygltf::Value& object, const char* key, double low, double high, double& out,
                    const std::string& file, const std::string& where) {
  if (!object.IsObject() || !object.Has(key)) return false;
  const tinygltf::Value& v = object.Get(key);
  const std::string at = pointer_join(where, key);
  require(v.IsNumber(), file, at, std::string(key) + " must be a number");
  out = v.GetNumberAsDouble();
  require(std::isfinite(out) && out >= low && out <= std::min(high, largest_material_value), file, at,
          std::string(key) + " must be finite and in [" + format_number(low) + ", " +
              format_number(std::min(high, largest_material_value)) + "]");
  return true;
}

void color_member(const tinygltf::Value& object, const char* key, vec3& out, const std::string& file,
                  const std::string& where) {
  if (!object.IsObject() || !object.Has(key)) return;
  const tinygltf::Value& color = object.Get(key);
  const std::string at = pointer_join(where, key);
  require(color.IsArray() && color.ArrayLen() == 3, file, at, std::string(key) + " must have 3 numbers");
  for (int i = 0; i < 3; ++i) {
    const tinygltf::Value& c = color.Get(i);
    require(c.IsNumber() && fits_float(c.GetNumberAsDouble()) && c.GetNumberAsDouble() >= 0.0, file, at,
            std::string(key) + " must be finite and not negative");
    out[i] = static_cast<float>(c.GetNumberAsDouble());
  }
}

texture_ref extension_texture(const tinygltf::Model& model, const tinygltf::Value& ext, const char* key,
                              texture_remap& remap, scene& out, const std::string& file,
                              const std::string& where) {
  if (!ext.IsObject() || !ext.Has(key)) return texture_ref{};
  const tinygltf::Value& info = ext.Get(key);
  const std::string at = pointer_join(where, key);
  require(info.IsObject() && info.Has("index") && info.Get("index").IsInt(), file, at,
          "textureInfo needs an integer index");
  const int index = info.Get("index").GetNumberAsInt();
  require(index >= 0 && size_t(index) < model.textures.size(), file, pointer_join(at, "index"),
          "texture " + std::to_string(index) + " does not exist");
  int texcoord = 0;
  if (info.Has("texCoord")) {
    require(info.Get("texCoord").IsInt() && info.Get("texCoord").GetNumberAsInt() >= 0, file,
            pointer_join(at, "texCoord"), "texCoord must be a non-negative integer");
    texcoord = info.Get("texCoord").GetNumberAsInt();
  }
  double scale = 1.0;  // a normalTextureInfo's
  bounded_number(info, "scale", -1e6, 1e6, scale, file, at);
  texture_ref ref = make_ref(model, index, texcoord, scale, remap, out, file);
  apply_texture_transform(transform_of(info), ref, file, at);
  return ref;
}

namespace {

// KHR_materials_transmission and KHR_materials_volume.
void convert_transmission(const tinygltf::Model& model, const tinygltf::Material& src, material& m,
                          texture_remap& remap, scene& out, const std::string& file,
                          const std::string& ext_where) {
  if (const tinygltf::Value* ext = find_extension(src, "KHR_materials_transmission")) {
    const std::string at = pointer_join(ext_where, "KHR_materials_transmission");
    double factor = 0.0;
    if (bounded_number(*ext, "transmissionFactor", 0.0, 1.0, factor, file, at))
      m.transmission_factor = static_cast<float>(factor);
    m.transmission_texture = extension_texture(model, *ext, "transmissionTexture", remap, out, file, at);
  }
  if (const tinygltf::Value* ext = find_extension(src, "KHR_materials_volume")) {
    const std::string at = pointer_join(ext_where, "KHR_materials_volume");
    double value = 0.0;
    if (bounded_number(*ext, "thicknessFactor", 0.0, largest_material_value, value, file, at))
      m.thickness_factor = static_cast<float>(value);
    if (bounded_number(*ext, "attenuationDistance", 0.0, largest_material_value, value, file, at)) {
      require(value > 0.0, file, pointer_join(at, "attenuationDistance"),
              "attenuationDistance must be positive");
      m.attenuation_distance = static_cast<float>(value);
    }
    color_member(*ext, "attenuationColor", m.attenuation_color, file, at);
  }
}

}  // namespace

texture_remap make_texture_remap(const tinygltf::Model& model) {
  texture_remap remap;
  remap.textures.assign(model.textures.size(), -1);
  remap.images.assign(model.images.size(), -1);
  remap.missing_source_warned.assign(model.textures.size(), 0);
  return remap;
}

void decode_used_images(texture_remap& remap, scene& out, const std::string& file, int threads) {
  std::vector<image> decoded = decode_images(remap.pending, file, remap.max_texels, threads, remap.memory);
  const size_t first = out.images.size() - decoded.size();
  for (size_t i = 0; i < decoded.size(); ++i) out.images[first + i] = std::move(decoded[i]);
  remap.pending.clear();
}

material default_material() {
  material m;
  m.name = "default";
  return m;  // scene.h's defaults are glTF's defaults
}

material convert_material(const tinygltf::Model& model, int index, texture_remap& remap, scene& out,
                          const std::string& file) {
  const tinygltf::Material& src = model.materials[static_cast<size_t>(index)];
  const std::string where = pointer("materials", index);
  const tinygltf::PbrMetallicRoughness& pbr = src.pbrMetallicRoughness;
  const std::string pbr_where = pointer_join(where, "pbrMetallicRoughness");

  material m;
  m.name = src.name;
  require(pbr.baseColorFactor.size() == 4, file, pointer_join(pbr_where, "baseColorFactor"),
          "baseColorFactor must have 4 numbers");
  for (int i = 0; i < 4; ++i) {
    const double v = pbr.baseColorFactor[static_cast<size_t>(i)];
    require(fits_float(v), file, pointer_join(pbr_where, "baseColorFactor"), "baseColorFactor is not finite");
    m.base_color_factor[i] = static_cast<float>(v);
  }
  require(fits_float(pbr.metallicFactor) && fits_float(pbr.roughnessFactor), file, pbr_where,
          "metallicFactor and roughnessFactor must be finite");
  m.metallic_factor = static_cast<float>(pbr.metallicFactor);
  m.roughness_factor = static_cast<float>(pbr.roughnessFactor);
  require(src.emissiveFactor.size() == 3, file, pointer_join(where, "emissiveFactor"),
          "emissiveFactor must have 3 numbers");
  for (int i = 0; i < 3; ++i) {
    const double v = src.emissiveFactor[static_cast<size_t>(i)];
    require(fits_float(v) && v >= 0.0, file, pointer_join(where, "emissiveFactor"),
            "emissiveFactor must be finite and not negative");
    m.emissive_factor[i] = static_cast<float>(v);
  }

  m.base_color_texture =
      make_ref(model, pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord, 1.0, remap, out, file);
  m.metallic_roughness_texture = make_ref(model, pbr.metallicRoughnessTexture.index,
                                          pbr.metallicRoughnessTexture.texCoord, 1.0, remap, out, file);
  m.emissive_texture =
      make_ref(model, src.emissiveTexture.index, src.emissiveTexture.texCoord, 1.0, remap, out, file);
  require(fits_float(src.normalTexture.scale) && fits_float(src.occlusionTexture.strength), file, where,
          "normalTexture.scale and occlusionTexture.strength must be finite");
  m.normal_texture = make_ref(model, src.normalTexture.index, src.normalTexture.texCoord,
                              src.normalTexture.scale, remap, out, file);
  apply_texture_transform(transform_of(pbr.baseColorTexture.extensions), m.base_color_texture, file,
                          pointer_join(pbr_where, "baseColorTexture"));
  apply_texture_transform(transform_of(pbr.metallicRoughnessTexture.extensions), m.metallic_roughness_texture,
                          file, pointer_join(pbr_where, "metallicRoughnessTexture"));
  apply_texture_transform(transform_of(src.emissiveTexture.extensions), m.emissive_texture, file,
                          pointer_join(where, "emissiveTexture"));
  apply_texture_transform(transform_of(src.normalTexture.extensions), m.normal_texture, file,
                          pointer_join(where, "normalTexture"));
  // occlusionTexture is checked like every texture but not converted: Whitted shading has no
  // ambient term for it to darken, so its image is never decoded.
  texture_ref unused_occlusion;
  apply_texture_transform(transform_of(src.occlusionTexture.extensions), unused_occlusion, file,
                          pointer_join(where, "occlusionTexture"));

  if (src.alphaMode == "OPAQUE")
    m.alpha = alpha_mode::opaque;
  else if (src.alphaMode == "MASK")
    m.alpha = alpha_mode::mask;
  else if (src.alphaMode == "BLEND")
    m.alpha = alpha_mode::blend;
  else
    throw input_error(file, pointer_join(where, "alphaMode"), "unknown alphaMode " + quoted(src.alphaMode));
  require(fits_float(src.alphaCutoff) && src.alphaCutoff >= 0.0, file, pointer_join(where, "alphaCutoff"),
          "alphaCutoff must be finite and not negative");
  m.alpha_cutoff = static_cast<float>(src.alphaCutoff);
  m.double_sided = src.doubleSided;

  const std::string ext_where = pointer_join(where, "extensions");
  if (const tinygltf::Value* ext = find_extension(src, "KHR_materials_emissive_strength")) {
    double strength = 1.0;
    if (extension_number(*ext, "emissiveStrength", strength)) {
      const std::string at =
          pointer_join(pointer_join(ext_where, "KHR_materials_emissive_strength"), "emissiveStrength");
      require(std::isfinite(strength) && strength >= 0.0, file, at,
              "emissiveStrength must be finite and not negative");
      // The emitted radiance is emissiveFactor × emissiveStrength, carried as float: past the
      // largest float it is infinite, and every sample that sees it is lost.
      const std::string largest = " past the largest float (" + format_number(largest_material_value) + ")";
      require(fits_float(strength), file, at,
              "emissiveStrength " + format_number(strength) + " is" + largest);
      const double radiance =
          strength * std::max({m.emissive_factor.x, m.emissive_factor.y, m.emissive_factor.z});
      require(fits_float(radiance), file, at,
              "emissiveStrength " + format_number(strength) + " times emissiveFactor is " +
                  format_number(radiance) + "," + largest);
      m.emissive_strength = static_cast<float>(strength);
    }
  }
  if (const tinygltf::Value* ext = find_extension(src, "KHR_materials_ior")) {
    double ior = 1.5;
    if (extension_number(*ext, "ior", ior)) {
      require(std::isfinite(ior) && (ior == 0.0 || ior >= 1.0), file,
              pointer_join(pointer_join(ext_where, "KHR_materials_ior"), "ior"),
              "ior must be 0 or at least 1");
      // KHR_materials_ior sets no maximum, so a huge ior is valid: it is kept at the largest float,
      // where reflectance has long been 1 in float (from an ior of about 1e8), the same surface.
      m.ior = static_cast<float>(std::min(ior, largest_material_value));
    }
  }
  if (const tinygltf::Value* ext = find_extension(src, "KHR_materials_specular")) {
    const std::string at = pointer_join(ext_where, "KHR_materials_specular");
    double factor = 1.0;
    if (extension_number(*ext, "specularFactor", factor)) {
      require(fits_float(factor) && factor >= 0.0, file, pointer_join(at, "specularFactor"),
              "specularFactor must be finite and not negative");
      m.specular_factor = static_cast<float>(factor);
    }
    color_member(*ext, "specularColorFactor", m.specular_color_factor, file, at);
    m.specular_texture = extension_texture(model, *ext, "specularTexture", remap, out, file, at);
    m.specular_color_texture = extension_texture(model, *ext, "specularColorTexture", remap, out, file, at);
  }
  convert_transmission(model, src, m, remap, out, file, ext_where);
  convert_material_lobes(model, src, m, remap, out, file, ext_where);
  m.unlit = find_extension(src, "KHR_materials_unlit") != nullptr;
  return m;
}

bool material_samples_texcoord0(const tinygltf::Model& model, int material_index) {
  if (material_index < 0) return false;
  for (const auto& [index, texcoord] : texture_slots(model.materials[static_cast<size_t>(material_index)]))
    if (index >= 0 && texcoord == 0) return true;
  return false;
}

bool material_samples_texcoord(const tinygltf::Model& model, int material_index, int set) {
  if (material_index < 0) return false;
  // A tangent frame generated from a UV set needs that set, textures or not (anisotropy).
  if (material_tangent_texcoord(model, material_index) == set) return true;
  for (const auto& [index, texcoord] : texture_slots(model.materials[static_cast<size_t>(material_index)]))
    if (index >= 0 && texcoord == set) return true;
  return false;
}

int material_tangent_texcoord(const tinygltf::Model& model, int material_index) {
  const tinygltf::Material& m = model.materials[static_cast<size_t>(material_index)];
  const tinygltf::NormalTextureInfo& info = m.normalTexture;
  if (info.index >= 0) return effective_texcoord(transform_of(info.extensions), info.texCoord);
  const auto [coat_index, coat_set] =
      extension_texture_slot(m, "KHR_materials_clearcoat", "clearcoatNormalTexture");
  if (coat_index >= 0) return coat_set;
  if (m.extensions.count("KHR_materials_anisotropy") == 0) return -1;
  const auto [index, set] = extension_texture_slot(m, "KHR_materials_anisotropy", "anisotropyTexture");
  return index >= 0 ? set : 0;
}

bool material_samples_other_texcoords(const tinygltf::Model& model, int material_index) {
  if (material_index < 0) return false;
  for (const auto& [index, texcoord] : texture_slots(model.materials[static_cast<size_t>(material_index)]))
    if (index >= 0 && texcoord > 1) return true;
  return false;
}

}  // namespace kiln::gltf_internal
