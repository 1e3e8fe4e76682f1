#include "io/exr/exr_writer.h"

#include <OpenImageIO/imageio.h>
#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <functional>
#include <limits>
#include <system_error>

#include "core/error.h"
#include "io/exr/atomic_write.h"
#include "io/exr/cryptomatte.h"
#include "io/exr/exr_header.h"

namespace kiln {
namespace fs = std::filesystem;

namespace {

// One channel of a layer: its full name (the same in single-part and multi-part files, so a reader
// that flattens parts finds the same names) and where its values come from.
struct channel {
  std::string name;
  std::function<float(size_t)> value;
};

// One layer of the file: what --multipart writes as one part, named so compositors show it as a
// layer (Nuke maps part "rgba" to its rgba layer and part "depth" with channel Z to depth.Z).
struct layer {
  std::string part;
  OIIO::TypeDesc format;
  // Data layers (depth, positions, ids) are always float and never stored with a lossy codec:
  // distances and positions need the precision, ids must stay exact integers.
  bool data = false;
  std::vector<channel> channels;
};

OIIO::TypeDesc type_of(sample_format format) {
  return format == sample_format::float32 ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::HALF;
}

// One Cryptomatte layer: ⌈depth/2⌉ RGBA sets named <name>00, <name>01, ..., each holding two
// ranks as (id, coverage, id, coverage); a rank past depth stays 0. Float: the ids are bit patterns.
layer cryptomatte_layer_of(const std::string& name, const std::vector<id_coverage>& ranks, int depth) {
  layer l{name, OIIO::TypeDesc::FLOAT, true, {}};
  const char* rgba[4] = {".R", ".G", ".B", ".A"};
  for (int set = 0; 2 * set < depth; ++set) {
    const std::string number = (set < 10 ? "0" : "") + std::to_string(set);
    for (int c = 0; c < 4; ++c) {
      const int rank = 2 * set + c / 2;
      const bool id = c % 2 == 0;
      l.channels.push_back({name + number + rgba[c], [&ranks, depth, rank, id](size_t i) {
                              if (rank >= depth) return 0.0f;
                              const id_coverage& r = ranks[i * size_t(depth) + size_t(rank)];
                              if (!id) return r.coverage;
                              float value;
                              std::memcpy(&value, &r.id, sizeof value);
                              return value;
                            }});
    }
  }
  return l;
}

// The layers of the film's AOVs, in the order of aov_list_name(). New layers (e.g. cryptomatte's)
// are one more entry here.
std::vector<layer> film_layers(const film& f, const exr_settings& settings) {
  std::vector<layer> out;
  const aov_set& a = f.aovs;
  const layer_formats& formats = settings.formats;
  const OIIO::TypeDesc full = OIIO::TypeDesc::FLOAT;
  // Three channels name.X name.Y name.Z (or .R .G .B) of a vec3 buffer.
  auto vec3_layer = [](const std::string& name, const char* const(&suffixes)[3], OIIO::TypeDesc format,
                       bool data, const std::vector<vec3>& buffer) {
    layer l{name, format, data, {}};
    for (int c = 0; c < 3; ++c)
      l.channels.push_back({name + suffixes[c], [&buffer, c](size_t i) { return buffer[i][c]; }});
    return l;
  };
  const char* const xyz[3] = {".X", ".Y", ".Z"};
  const char* const rgb[3] = {".R", ".G", ".B"};
  if (a.beauty) {
    layer l{exr_part_name(exr_part::rgba), type_of(formats.beauty), false, {}};
    // Half's largest finite value is 65504: a brighter colour would become +inf in a half channel,
    // and the image holds no infinities but background Z, so half colour saturates there instead.
    const float limit = l.format == full ? std::numeric_limits<float>::max() : 65504.0f;
    const char* rgba[4] = {"R", "G", "B", "A"};
    for (int c = 0; c < 4; ++c)
      l.channels.push_back(
          {rgba[c], [&f, c, limit](size_t i) { return std::clamp(f.color[i][c], -limit, limit); }});
    out.push_back(std::move(l));
  }
  if (a.depth)
    out.push_back(
        {exr_part_name(exr_part::depth), full, true, {{"Z", [&f](size_t i) { return f.depth[i]; }}}});
  if (a.normal)
    out.push_back(vec3_layer(exr_part_name(exr_part::normal), xyz, type_of(formats.normal), false, f.normal));
  if (a.position) out.push_back(vec3_layer(exr_part_name(exr_part::position), xyz, full, true, f.position));
  if (a.albedo)
    out.push_back(vec3_layer(exr_part_name(exr_part::albedo), rgb, type_of(formats.albedo), false, f.albedo));
  if (a.uv)
    out.push_back(
        {exr_part_name(exr_part::uv),
         type_of(formats.uv),
         false,
         {{"uv.U", [&f](size_t i) { return f.uv[i].x; }}, {"uv.V", [&f](size_t i) { return f.uv[i].y; }}}});
  if (a.ids) {
    layer l{exr_part_name(exr_part::id), full, true, {}};
    const char* id_names[3] = {"id.object", "id.material", "id.instance"};
    for (int c = 0; c < 3; ++c)
      l.channels.push_back({id_names[c], [&f, c](size_t i) { return float(f.ids[i][c]); }});
    out.push_back(std::move(l));
  }
  // The light split: colour like R G B, each in its own format and saturating like the beauty.
  struct split_part {
    bool wanted;
    const std::vector<vec3>* buffer;
    exr_part part;
    sample_format format;
  };
  const split_part parts[3] = {{a.direct, &f.direct, exr_part::direct, formats.direct},
                               {a.reflection, &f.reflection, exr_part::reflection, formats.reflection},
                               {a.refraction, &f.refraction, exr_part::refraction, formats.refraction}};
  const std::string part_names[3] = {exr_part_name(exr_part::direct), exr_part_name(exr_part::reflection),
                                     exr_part_name(exr_part::refraction)};
  for (int p = 0; p < 3; ++p) {
    if (!parts[p].wanted) continue;
    layer l{part_names[p], type_of(parts[p].format), false, {}};
    const float limit = l.format == full ? std::numeric_limits<float>::max() : 65504.0f;
    for (int c = 0; c < 3; ++c)
      l.channels.push_back({part_names[p] + rgb[c], [buffer = parts[p].buffer, c, limit](size_t i) {
                              return std::clamp((*buffer)[i][c], -limit, limit);
                            }});
    out.push_back(std::move(l));
  }
  if (a.crypto_object) out.push_back(cryptomatte_layer_of(crypto_object_layer_name, f.crypto_object, a.crypto_depth));
  if (a.crypto_material)
    out.push_back(cryptomatte_layer_of(crypto_material_layer_name, f.crypto_material, a.crypto_depth));
  return out;
}

void check_layers(const std::vector<layer>& layers, const exr_settings& settings) {
  if (settings.multipart || !is_lossy_compression(settings.compression)) return;
  for (const layer& l : layers)
    if (l.data)
      throw input_error(
          "", "--compression",
          settings.compression +
              " is lossy and a single-part EXR has one codec for all channels, "
              "so it would alter " +
              l.channels.front().name +
              "; add --multipart (data layers then keep zip) or pick none, rle, zips, zip or piz");
}

// OpenImageIO's compression attribute: "zip", or with a level "zip:4" / "dwaa:45". Data layers
// of a multi-part file whose codec is lossy get plain zip.
std::string compression_attribute(const exr_settings& settings, bool data) {
  if (data && is_lossy_compression(settings.compression)) return "zip";
  if (settings.compression_level > 0 && compression_takes_level(settings.compression))
    return settings.compression + ":" + std::to_string(settings.compression_level);
  return settings.compression;
}

// The header every part carries: windows, colour space, camera matrices, metadata, tiling.
OIIO::ImageSpec base_spec(const film& f, const exr_settings& settings, const exr_metadata& metadata) {
  OIIO::ImageSpec spec(f.width, f.height, 0, OIIO::TypeDesc::FLOAT);
  // The data window is the stored region; the display window the full frame (they differ for crops).
  spec.x = f.x0;
  spec.y = f.y0;
  spec.full_x = 0;
  spec.full_y = 0;
  spec.full_width = f.full_width;
  spec.full_height = f.full_height;
  if (settings.tile_size > 0) {
    spec.tile_width = settings.tile_size;
    spec.tile_height = settings.tile_size;
    spec.tile_depth = 1;
  }
  spec.attribute("oiio:ColorSpace", "Linear");
  // Rec.709 primaries and D65 white: glTF's linear colour space.
  const float chromaticities[8] = {0.64f, 0.33f, 0.30f, 0.60f, 0.15f, 0.06f, 0.3127f, 0.3290f};
  spec.attribute("chromaticities", OIIO::TypeDesc(OIIO::TypeDesc::FLOAT, 8), chromaticities);
  // OpenEXR stores matrices row-major with row vectors (p' = p·M): the transpose of GLM's
  // column-vector convention, which in memory equals GLM's column-major layout.
  float world_to_camera[16];
  float world_to_ndc[16];
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) {
      world_to_camera[c * 4 + r] = float(metadata.world_to_camera[c][r]);
      world_to_ndc[c * 4 + r] = float(metadata.world_to_ndc[c][r]);
    }
  spec.attribute("worldToCamera", OIIO::TypeMatrix44, world_to_camera);
  spec.attribute("worldToNDC", OIIO::TypeMatrix44, world_to_ndc);
  spec.attribute("Software", std::string("kiln ") + KILN_VERSION);
  for (const auto& [key, value] : metadata.attributes) spec.attribute(key, value);
  for (const auto& [key, value] : metadata.float_attributes) spec.attribute(key, value);
  for (const auto& [key, value] : metadata.int_attributes) spec.attribute(key, value);
  return spec;
}

// A part holding layers: the base header with their channels, formats and codec.
OIIO::ImageSpec part_spec(OIIO::ImageSpec spec, const std::vector<const layer*>& layers,
                          const exr_settings& settings) {
  bool data = false;
  for (const layer* l : layers) {
    for (const channel& c : l->channels) {
      spec.channelnames.push_back(c.name);
      spec.channelformats.push_back(l->format);
    }
    data = data || l->data;
  }
  spec.nchannels = int(spec.channelnames.size());
  const auto index = [&spec](const char* name) {
    auto it = std::find(spec.channelnames.begin(), spec.channelnames.end(), name);
    return it == spec.channelnames.end() ? -1 : int(it - spec.channelnames.begin());
  };
  spec.alpha_channel = index("A");
  spec.z_channel = index("Z");
  spec.attribute("compression", compression_attribute(settings, data));
  if (layers.size() == 1 && settings.multipart) spec.attribute("oiio:subimagename", layers.front()->part);
  return spec;
}

// The pixels of layers as interleaved float, in the order of part_spec's channels.
std::vector<float> interleave(size_t pixel_count, const std::vector<const layer*>& layers) {
  std::vector<const channel*> channels;
  for (const layer* l : layers)
    for (const channel& c : l->channels) channels.push_back(&c);
  const size_t n = channels.size();
  std::vector<float> pixels(pixel_count * n);
  for (size_t i = 0; i < pixel_count; ++i)
    for (size_t c = 0; c < n; ++c) pixels[i * n + c] = channels[c]->value(i);
  return pixels;
}

// Writes parts (one spec and one pixel buffer, in format, each) atomically: a single-part file, or
// a multi-part one opened with every part's spec and filled part by part.
void write_parts(const std::string& path, const std::vector<OIIO::ImageSpec>& specs,
                 const std::vector<const void*>& pixels, OIIO::TypeDesc format) {
  write_atomically(path, "EXR", [&](const std::string& temporary) -> std::string {
    auto out = OIIO::ImageOutput::create("openexr");
    if (!out) return "OpenImageIO has no openexr writer: " + OIIO::geterror();
    if (specs.size() > 1 && !out->supports("multiimage")) return "the EXR writer cannot write parts";
    bool ok = specs.size() == 1 ? out->open(temporary, specs.front())
                                : out->open(temporary, int(specs.size()), specs.data());
    for (size_t part = 0; ok && part < specs.size(); ++part) {
      if (part > 0) ok = out->open(temporary, specs[part], OIIO::ImageOutput::AppendSubimage);
      ok = ok && out->write_image(format, pixels[part]);
    }
    ok = out->close() && ok;
    const std::string reason = ok ? std::string() : out->geterror();
    return ok || !reason.empty() ? reason : std::string("rename failed");
  });
}

}  // namespace

void check_output_writable(const std::string& path) {
  fs::path target(path);
  if (target.filename().empty()) throw io_error(path, "output path names a folder, not a file");
  fs::path folder = target.parent_path().empty() ? fs::path(".") : target.parent_path();
  std::error_code ec;
  if (!fs::is_directory(folder, ec)) throw io_error(path, "output folder does not exist: " + folder.string());
  if (::access(folder.c_str(), W_OK) != 0)
    throw io_error(path, "output folder is not writable: " + folder.string());
  if (fs::is_directory(target, ec)) throw io_error(path, "output path is a folder");
  // The temporary file is renamed over the target: that must never replace a device, a pipe or
  // a socket.
  if (fs::exists(target, ec) && !fs::is_regular_file(target, ec))
    throw io_error(path, "output exists and is not a regular file");
  // access() answers yes to root for any folder, including /proc and /sys where nothing can be
  // created, so create the temporary file the writer will use, and remove it again.
  const std::string probe = temporary_path(path);
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd < 0) {
    if (errno == EEXIST) return;  // a stale temporary of this process id: the writer replaces it
    throw io_error(path,
                   "output folder is not writable: " + folder.string() + " (" + std::strerror(errno) + ")");
  }
  ::close(fd);
  ::unlink(probe.c_str());
}

void check_exr_settings(const aov_set& aovs, const exr_settings& settings) {
  film shape;  // no pixels: only which layers exist matters
  shape.aovs = aovs;
  check_layers(film_layers(shape, settings), settings);
}

void write_exr(const std::string& path, const film& f, const exr_settings& settings,
               const exr_metadata& metadata) {
  check_output_writable(path);
  if (f.width <= 0 || f.height <= 0 || f.color.size() != size_t(f.width) * f.height)
    throw io_error(path, "refusing to write an empty or inconsistent image");
  const std::vector<layer> layers = film_layers(f, settings);
  if (layers.empty()) throw io_error(path, "refusing to write an image without channels");
  check_layers(layers, settings);
  // One part with every layer, or one part per layer.
  std::vector<std::vector<const layer*>> parts;
  for (const layer& l : layers)
    if (settings.multipart || parts.empty())
      parts.push_back({&l});
    else
      parts.front().push_back(&l);
  const OIIO::ImageSpec base = base_spec(f, settings, metadata);
  std::vector<OIIO::ImageSpec> specs;
  std::vector<std::vector<float>> pixels;
  std::vector<const void*> buffers;
  for (const auto& part : parts) {
    specs.push_back(part_spec(base, part, settings));
    pixels.push_back(interleave(size_t(f.width) * f.height, part));
    buffers.push_back(pixels.back().data());
  }
  write_parts(path, specs, buffers, OIIO::TypeDesc::FLOAT);
}

void write_exr(const std::string& path, const exr_image& image) {
  check_output_writable(path);
  const pixel_rect& d = image.data_window;
  if (!image.header || image.header->parts.empty() || d.width() <= 0 || d.height() <= 0 ||
      image.pixels.size() != size_t(d.width()) * size_t(d.height()) * image.pixel_bytes())
    throw io_error(path, "refusing to write an empty or inconsistent image");
  // Split the image's interleaved pixels back into its parts, each in its own channel formats.
  const size_t pixel_count = size_t(d.width()) * size_t(d.height());
  const size_t pixel = image.pixel_bytes();
  std::vector<OIIO::ImageSpec> specs;
  std::vector<std::vector<unsigned char>> pixels;
  std::vector<const void*> buffers;
  size_t offset = 0;
  for (OIIO::ImageSpec spec : image.header->parts) {
    spec.x = d.x0;
    spec.y = d.y0;
    spec.width = d.width();
    spec.height = d.height();
    const size_t part_pixel = spec.pixel_bytes(true);
    if (offset + part_pixel > pixel) throw io_error(path, "refusing to write an inconsistent image");
    std::vector<unsigned char> part(pixel_count * part_pixel);
    for (size_t i = 0; i < pixel_count; ++i)
      std::memcpy(part.data() + i * part_pixel, image.pixels.data() + i * pixel + offset, part_pixel);
    offset += part_pixel;
    specs.push_back(spec);
    pixels.push_back(std::move(part));
    buffers.push_back(pixels.back().data());
  }
  // TypeUnknown: the pixels are in the specs' own per-channel formats.
  write_parts(path, specs, buffers, OIIO::TypeUnknown);
}

}  // namespace kiln
