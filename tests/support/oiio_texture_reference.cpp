#include "support/oiio_texture_reference.h"

#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imagecache.h>
#include <OpenImageIO/imageio.h>
#include <OpenImageIO/texture.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <string>
#include <vector>

namespace kiln::testing {

namespace {

// Where the ImageCache finds an image's pixels: ImageInput::Creator is a plain function pointer,
// so the source travels in the configuration spec that ImageCache::add_file hands to open().
// Level 0 is the scene image itself, decoded per scanline; the coarser levels are built once, in
// linear float, each the 2×2 box average of the level above (OpenImageIO's resize, "box").
struct memory_source {
  const image* pixels = nullptr;
  texel_encoding encoding = texel_encoding::linear;
  std::vector<OIIO::ImageBuf> coarser;  // levels 1, 2, ... down to 1×1

  int levels() const { return 1 + int(coarser.size()); }
  int width(int level) const { return level == 0 ? pixels->width : coarser[size_t(level - 1)].spec().width; }
  int height(int level) const {
    return level == 0 ? pixels->height : coarser[size_t(level - 1)].spec().height;
  }
};

// Level 0 as a float buffer (temporary: only the first box average reads it). Rows in parallel on
// the caller's arena; each texel is converted on its own, so the result does not depend on it.
OIIO::ImageBuf level0_buffer(const image& img, texel_encoding encoding) {
  OIIO::ImageBuf buf(OIIO::ImageSpec(img.width, img.height, 4, OIIO::TypeDesc::FLOAT));
  float* out = static_cast<float*>(buf.localpixels());
  tbb::parallel_for(0, img.height, [&](int y) {
    for (int x = 0; x < img.width; ++x) {
      const vec4 t = fetch_texel(img, x, y, encoding);
      for (int c = 0; c < 4; ++c) out[(size_t(y) * img.width + x) * 4 + c] = t[c];
    }
  });
  return buf;
}

// OpenGL's pyramid: each level halves both sides (rounding down, never below 1) until 1×1.
std::vector<OIIO::ImageBuf> build_coarser_levels(const image& img, texel_encoding encoding) {
  std::vector<OIIO::ImageBuf> levels;
  OIIO::ImageBuf finer = level0_buffer(img, encoding);
  int w = img.width, h = img.height;
  while (w > 1 || h > 1) {
    w = std::max(1, w / 2);
    h = std::max(1, h / 2);
    // One thread: kiln's own thread count governs; the result does not depend on it anyway.
    // (Bands of rows in parallel measured no faster: the pyramids already run in parallel.)
    OIIO::ImageBuf next =
        OIIO::ImageBufAlgo::resize(finer, "box", 0.0f, OIIO::ROI(0, w, 0, h, 0, 1, 0, 4), 1);
    levels.push_back(next);
    finer = std::move(next);
  }
  return levels;
}

constexpr const char* source_attribute = "kiln:memory_source";

// An ImageInput that reads a mip-mapped scene image from memory, as linear float RGBA scanlines.
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
    if (!seek_subimage(0, 0)) return false;
    newspec = m_spec;
    return true;
  }

  int current_miplevel() const override { return level_; }

  bool seek_subimage(int subimage, int miplevel) override {
    if (!source_ || subimage != 0 || miplevel < 0 || miplevel >= source_->levels()) return false;
    level_ = miplevel;
    m_spec = OIIO::ImageSpec(source_->width(level_), source_->height(level_), 4, OIIO::TypeDesc::FLOAT);
    return true;
  }

  bool close() override { return true; }

  bool read_native_scanline(int subimage, int miplevel, int y, int, void* data) override {
    if (!source_ || subimage != 0 || miplevel < 0 || miplevel >= source_->levels() || y < 0 ||
        y >= source_->height(miplevel))
      return false;
    float* out = static_cast<float*>(data);
    const int w = source_->width(miplevel);
    if (miplevel > 0) {
      const float* row = static_cast<const float*>(source_->coarser[size_t(miplevel - 1)].localpixels());
      std::copy(row + size_t(y) * w * 4, row + size_t(y + 1) * w * 4, out);
      return true;
    }
    for (int x = 0; x < w; ++x) {
      const vec4 t = fetch_texel(*source_->pixels, x, y, source_->encoding);
      for (int c = 0; c < 4; ++c) out[4 * x + c] = t[c];
    }
    return true;
  }

 private:
  const memory_source* source_ = nullptr;
  int level_ = 0;
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

// Per texture and encoding (see slot()): whether some material reads it through a mip-mapped
// sampler.
std::vector<bool> mip_mapped_uses(const scene& s) {
  std::vector<bool> used(s.textures.size() * 2, false);
  for (const material& m : s.materials)
    for (const texture_slot& t : texture_slots(m))
      if (t.ref->present() && s.textures[size_t(t.ref->texture)].sampling.mipmap != mip_mode::none)
        used[slot(uint32_t(t.ref->texture), t.encoding)] = true;
  return used;
}

// One ImageCache and TextureSystem for the whole process, never destroyed. OpenImageIO keeps each
// cache's per-thread state in thread-specific storage that ImageCache::destroy does not clear on
// the other threads, so a later cache in the same process (the next asset of `kiln batch`) found
// the freed state of the last one on every thread that had used it: decr_tiles' assertion, or a
// crash. Renders use it one at a time, each under file names of its own (a render number), and
// invalidate their files when done, which frees their tiles.
struct process_texture_system {
  OIIO::ImageCache* cache = nullptr;
  OIIO::TextureSystem* system = nullptr;
  std::atomic<uint64_t> renders{0};
};

process_texture_system& shared_texture_system() {
  static process_texture_system* shared = [] {
    auto* p = new process_texture_system;  // deliberately never freed (see above)
    p->cache = OIIO::ImageCache::create(false);
    p->cache->attribute("autotile", 64);
    p->cache->attribute("forcefloat", 1);
    p->cache->attribute("deduplicate", 0);
    p->system = OIIO::TextureSystem::create(false, p->cache);
    return p;
  }();
  return *shared;
}

}  // namespace

struct oiio_texture_reference::impl {
  OIIO::ImageCache* cache = nullptr;
  OIIO::TextureSystem* system = nullptr;
  std::vector<memory_source> sources;  // per image and encoding; never reallocated after setup
  std::vector<OIIO::ustring> files;    // this render's names in the shared cache
  struct lookup {
    OIIO::TextureSystem::TextureHandle* handle = nullptr;
    OIIO::TextureOpt options;
  };
  std::vector<lookup> lookups;  // per texture and encoding (see slot())

  ~impl() {
    // Closes the files and drops their tiles; the names are never used again.
    for (const OIIO::ustring& name : files) cache->invalidate(name, true);
  }
};

oiio_texture_reference::oiio_texture_reference(const scene& s, float cache_mb)
    : impl_(std::make_unique<impl>()) {
  // Nothing is shared with the loader's decoding. The in-memory scanline images are cut into 64²
  // tiles as they are read. Their pyramids are built here rather than by the cache's automip, which
  // resamples texel by texel through the cache and, with a cache smaller than the textures,
  // recomputes evicted levels over and over.
  process_texture_system& shared = shared_texture_system();
  impl_->cache = shared.cache;
  impl_->system = shared.system;
  impl_->cache->attribute("max_memory_MB", cache_mb);
  const std::string prefix = "kiln:render" + std::to_string(shared.renders++) + "/image/";

  // Pyramids only for the (image, encoding) pairs that a mip-mapped sampler reads. They are
  // independent, so they are built in parallel (on the caller's arena: the render's threads); this
  // runs before the first pixel, and one thread building them all held two-thread renders of
  // textured assets well under twice the speed of one.
  const std::vector<bool> used = mip_mapped_uses(s);
  impl_->sources.resize(s.images.size() * 2);
  std::vector<memory_source*> to_build;
  for (size_t t = 0; t < s.textures.size(); ++t)
    for (texel_encoding e : {texel_encoding::linear, texel_encoding::srgb}) {
      if (!used[slot(uint32_t(t), e)]) continue;
      const uint32_t i = s.textures[t].image;
      memory_source& source = impl_->sources[slot(i, e)];
      if (source.pixels || s.images[i].width <= 0 || s.images[i].height <= 0) continue;
      source.pixels = &s.images[i];
      source.encoding = e;
      to_build.push_back(&source);
    }
  tbb::parallel_for(size_t(0), to_build.size(), [&](size_t k) {
    to_build[k]->coarser = build_coarser_levels(*to_build[k]->pixels, to_build[k]->encoding);
  });

  impl_->lookups.resize(s.textures.size() * 2);
  for (size_t t = 0; t < s.textures.size(); ++t) {
    const texture& tex = s.textures[t];
    for (texel_encoding e : {texel_encoding::linear, texel_encoding::srgb}) {
      const memory_source& source = impl_->sources[slot(tex.image, e)];
      if (!used[slot(uint32_t(t), e)] || !source.pixels) continue;
      const OIIO::ustring name(prefix + std::to_string(tex.image) +
                               (e == texel_encoding::srgb ? "/srgb" : "/linear"));
      OIIO::ImageSpec config;
      const memory_source* source_pointer = &source;
      config.attribute(source_attribute, OIIO::TypeDesc::PTR, &source_pointer);
      impl_->cache->add_file(name, create_memory_input, &config);
      impl_->files.push_back(name);
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

oiio_texture_reference::~oiio_texture_reference() = default;

vec4 oiio_texture_reference::minified(uint32_t texture_index, texel_encoding encoding, vec2 uv,
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

}  // namespace kiln::testing
