#include "scene/colour_conversion.h"

#include <cmath>
#include <map>

#include "core/error.h"
#include "scene/texture_eval.h"

namespace kiln {
namespace {

vec3 convert(const mat3& m, vec3 c) { return m * c; }

// Which images the scene reads as colour (through an sRGB slot) and which as data.
struct image_uses {
  std::vector<bool> colour, data;
};

image_uses find_image_uses(const scene& s) {
  image_uses uses{std::vector<bool>(s.images.size(), false), std::vector<bool>(s.images.size(), false)};
  for (const material& m : s.materials)
    for (const texture_slot& slot : texture_slots(m)) {
      if (!slot.ref || !slot.ref->present() || size_t(slot.ref->texture) >= s.textures.size()) continue;
      const uint32_t image = s.textures[size_t(slot.ref->texture)].image;
      if (image >= s.images.size()) continue;
      (slot.encoding == texel_encoding::srgb ? uses.colour : uses.data)[image] = true;
    }
  if (s.env.has_map() && size_t(s.env.map_image) < s.images.size()) uses.data[size_t(s.env.map_image)] = true;
  return uses;
}

// Converts img's texels in place, read and written with encoding (alpha untouched); the result is float.
void convert_image(image& img, const mat3& m, texel_encoding encoding) {
  const size_t texels = size_t(img.width) * size_t(img.height);
  std::vector<float> out(texels * 4);
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const vec4 t = fetch_texel(img, x, y, encoding);
      const vec3 c = convert(m, vec3(t));
      float* o = &out[(size_t(y) * size_t(img.width) + size_t(x)) * 4];
      for (int k = 0; k < 3; ++k) o[k] = encoding == texel_encoding::srgb ? linear_to_srgb(c[k]) : c[k];
      o[3] = t.a;
    }
  img.texels8.clear();
  img.texels8.shrink_to_fit();
  img.texels32 = std::move(out);
}

uint64_t image_bytes(const image& img) { return img.texels8.size() + img.texels32.size() * sizeof(float); }

// The texture a colour slot reads after conversion: itself, or a copy of it on the converted copy
// of its image when a data slot shares that image.
int32_t colour_texture(scene& s, int32_t index, const std::map<uint32_t, uint32_t>& copied_images,
                       std::map<int32_t, int32_t>& copied_textures) {
  const uint32_t image = s.textures[size_t(index)].image;
  const auto copy = copied_images.find(image);
  if (copy == copied_images.end()) return index;
  if (const auto done = copied_textures.find(index); done != copied_textures.end()) return done->second;
  texture t = s.textures[size_t(index)];
  t.image = copy->second;
  s.textures.push_back(t);
  return copied_textures[index] = int32_t(s.textures.size() - 1);
}

void convert_textures(scene& s, const mat3& m, bool allow_copies, uint64_t& grown) {
  const image_uses uses = find_image_uses(s);
  std::map<uint32_t, uint32_t> copied_images;  // shared image -> its colour copy
  const size_t file_images = s.images.size();
  for (size_t i = 0; i < file_images; ++i) {
    if (!uses.colour[i]) continue;
    uint32_t target = uint32_t(i);
    if (uses.data[i]) {
      if (!allow_copies)
        throw input_error(s.source, "--working-space",
                          "image " + std::to_string(i) +
                              " is read both as colour and as data; with --frames "
                              "a working space needs each image used one way (render the frames one by one)");
      s.images.push_back(s.images[i]);
      target = uint32_t(s.images.size() - 1);
      copied_images[uint32_t(i)] = target;
      grown += image_bytes(s.images[i]);
    }
    const uint64_t before = image_bytes(s.images[target]);
    convert_image(s.images[target], m, texel_encoding::srgb);
    grown += image_bytes(s.images[target]) - before;
  }
  if (copied_images.empty()) return;
  std::map<int32_t, int32_t> copied_textures;
  for (material& mat : s.materials)
    for (texture_ref* ref : {&mat.base_color_texture, &mat.emissive_texture})
      if (ref->present() && size_t(ref->texture) < s.textures.size())
        ref->texture = colour_texture(s, ref->texture, copied_images, copied_textures);
}

}  // namespace

float linear_to_srgb(float v) {
  return v <= 0.0031308f ? v * 12.92f : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
}

uint64_t convert_scene_colours(scene& s, const mat3& working_from_rec709,
                               const colour_conversion_scope& scope) {
  const mat3& m = working_from_rec709;
  // What every pose builds again.
  for (light& l : s.lights) l.color = convert(m, l.color);
  s.env.color = convert(m, s.env.color);
  const auto convert_mesh = [&](mesh& me) {
    for (vec4& c : me.colors0) c = vec4(convert(m, vec3(c)), c.a);
  };
  if (scope.carried_over) {
    if (scope.posed_meshes)
      for (uint32_t i : *scope.posed_meshes)
        if (i < s.meshes.size()) convert_mesh(s.meshes[i]);
    return 0;
  }
  for (mesh& me : s.meshes) convert_mesh(me);
  for (material& mat : s.materials) {
    mat.base_color_factor = vec4(convert(m, vec3(mat.base_color_factor)), mat.base_color_factor.a);
    mat.emissive_factor = convert(m, mat.emissive_factor);
    mat.specular_color_factor = convert(m, mat.specular_color_factor);
    // Beer-Lambert absorption is exponential in this colour, so converting it is exact only for
    // grey attenuation; it is still the colour the file means, in the working space's terms.
    mat.attenuation_color = convert(m, mat.attenuation_color);
  }
  uint64_t grown = 0;
  convert_textures(s, m, scope.allow_image_copies, grown);
  if (s.env.has_map() && size_t(s.env.map_image) < s.images.size()) {
    image& map = s.images[size_t(s.env.map_image)];
    const uint64_t before = image_bytes(map);
    convert_image(map, m, texel_encoding::linear);
    grown += image_bytes(map) - before;
  }
  return grown;
}

}  // namespace kiln
