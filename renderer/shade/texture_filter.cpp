#include "shade/texture_filter.h"

#include <OpenImageIO/imagecache.h>
#include <OpenImageIO/imageio.h>
#include <OpenImageIO/texture.h>

#include <string>
#include <vector>

namespace kiln {

namespace {

// Where the ImageCache finds an image's pixels: ImageInput::Creator is a plain function pointer,
// so the source travels in the configuration spec that ImageCache::add_file hands to open().
struct memory_source {
  const image* pixels = nullptr;
  texel_encoding encoding = texel_encoding::linear;
};

constexpr const char* source_attribute = "kiln:memory_source";

// An ImageInput that reads a decoded scene image from memory, as linear float RGBA.
class memory_image_input final : public OIIO::ImageInput {
 public:
  const char* format_name() const override { return "kiln_memory"; }

  bool open(const std::string& name, OIIO::ImageSpec&) override {
    errorfmt("{}: an in-memory image needs its source in the configuration", name);
    return false;
  }

  bool open(const std::string& name, OIIO::ImageSpec& newspec, const OIIO::ImageSpec& config) override {
    const OIIO::ParamValue* p = config.find_attribute(source_attribute, OIIO::TypeDesc::PTR);
    if (!p) return open(name, newspec);
    source_ = static_cast<const memory_source*>(p->get<void*>());
    m_spec = OIIO::ImageSpec(source_->pixels->width, source_->pixels->height, 4, OIIO::TypeDesc::FLOAT);
    newspec = m_spec;
    return true;
  }

  bool close() override { return true; }

  bool read_native_scanline(int subimage, int miplevel, int y, int, void* data) override {
    if (subimage != 0 || miplevel != 0 || !source_ || y < 0 || y >= source_->pixels->height) return false;
    float* out = static_cast<float*>(data);
    for (int x = 0; x < source_->pixels->width; ++x) {
      const vec4 t = fetch_texel(*source_->pixels, x, y, source_->encoding);
      for (int c = 0; c < 4; ++c) out[4 * x + c] = t[c];
    }
    return true;
  }

 private:
  const memory_source* source_ = nullptr;
};

OIIO::ImageInput* create_memory_input() { return new memory_image_input; }

OIIO::TextureOpt::Wrap to_oiio(wrap_mode mode) {
  switch (mode) {
    case wrap_mode::clamp_to_edge:
      return OIIO::TextureOpt::WrapClamp;
    case wrap_mode::mirrored_repeat:
      return OIIO::TextureOpt::WrapMirror;
    case wrap_mode::repeat:
    default:
      return OIIO::TextureOpt::WrapPeriodic;
  }
}

size_t slot(uint32_t texture_index, texel_encoding encoding) {
  return size_t(texture_index) * 2 + (encoding == texel_encoding::srgb ? 1 : 0);
}

}  // namespace

struct texture_filter::impl {
  OIIO::ImageCache* cache = nullptr;
  OIIO::TextureSystem* system = nullptr;
  std::vector<memory_source> sources;  // per image and encoding; never reallocated after setup
  struct lookup {
    OIIO::TextureSystem::TextureHandle* handle = nullptr;
    OIIO::TextureOpt options;
  };
  std::vector<lookup> lookups;  // per texture and encoding (see slot())

  ~impl() {
    if (system) OIIO::TextureSystem::destroy(system);
    if (cache) OIIO::ImageCache::destroy(cache);
  }
};

texture_filter::texture_filter(const scene& s, float cache_mb) : impl_(std::make_unique<impl>()) {
  // A private cache: nothing is shared with other renders or with the loader's decoding. Untiled
  // in-memory images are cut into 64² tiles and automipped on demand; each coarser level's texel is
  // OpenImageIO's bilinear resample of the finer level (a 2×2 box for power-of-two sizes).
  impl_->cache = OIIO::ImageCache::create(false);
  impl_->cache->attribute("max_memory_MB", cache_mb);
  impl_->cache->attribute("autotile", 64);
  impl_->cache->attribute("automip", 1);
  impl_->cache->attribute("forcefloat", 1);
  impl_->cache->attribute("deduplicate", 0);
  impl_->system = OIIO::TextureSystem::create(false, impl_->cache);

  impl_->sources.resize(s.images.size() * 2);
  for (size_t i = 0; i < s.images.size(); ++i)
    for (texel_encoding e : {texel_encoding::linear, texel_encoding::srgb})
      impl_->sources[slot(uint32_t(i), e)] = memory_source{&s.images[i], e};

  impl_->lookups.resize(s.textures.size() * 2);
  for (size_t t = 0; t < s.textures.size(); ++t) {
    const texture& tex = s.textures[t];
    if (tex.sampling.mipmap == mip_mode::none) continue;
    const image& img = s.images[tex.image];
    if (img.width <= 0 || img.height <= 0) continue;
    for (texel_encoding e : {texel_encoding::linear, texel_encoding::srgb}) {
      const memory_source& source = impl_->sources[slot(tex.image, e)];
      const OIIO::ustring name("kiln:image/" + std::to_string(tex.image) +
                               (e == texel_encoding::srgb ? "/srgb" : "/linear"));
      OIIO::ImageSpec config;
      const memory_source* source_pointer = &source;
      config.attribute(source_attribute, OIIO::TypeDesc::PTR, &source_pointer);
      impl_->cache->add_file(name, create_memory_input, &config);
      impl::lookup& l = impl_->lookups[slot(uint32_t(t), e)];
      l.handle = impl_->system->get_texture_handle(name);
      l.options.swrap = to_oiio(tex.sampling.wrap_s);
      l.options.twrap = to_oiio(tex.sampling.wrap_t);
      l.options.mipmode = tex.sampling.mipmap == mip_mode::nearest ? OIIO::TextureOpt::MipModeOneLevel
                                                                   : OIIO::TextureOpt::MipModeAniso;
      l.options.interpmode = tex.sampling.min_filter == filter_mode::nearest
                                 ? OIIO::TextureOpt::InterpClosest
                                 : OIIO::TextureOpt::InterpBilinear;
    }
  }
}

texture_filter::~texture_filter() = default;

vec4 texture_filter::minified(uint32_t texture_index, texel_encoding encoding, vec2 uv,
                              const uv_footprint& footprint) const {
  const impl::lookup& l = impl_->lookups[slot(texture_index, encoding)];
  if (!l.handle) return vec4(1.0f);
  OIIO::TextureOpt options = l.options;  // texture() may write to its options
  float result[4] = {1.0f, 1.0f, 1.0f, 1.0f};
  OIIO::TextureSystem::Perthread* thread_info = impl_->system->get_perthread_info();
  if (!impl_->system->texture(l.handle, thread_info, options, uv.x, uv.y, footprint.dx.x, footprint.dx.y,
                              footprint.dy.x, footprint.dy.y, 4, result))
    return vec4(1.0f);
  return {result[0], result[1], result[2], result[3]};
}

bool scene_needs_texture_filter(const scene& s) {
  for (const texture& t : s.textures)
    if (t.sampling.mipmap != mip_mode::none) return true;
  return false;
}

}  // namespace kiln
