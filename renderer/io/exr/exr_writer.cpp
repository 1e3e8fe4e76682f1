#include "io/exr/exr_writer.h"

#include <Imath/half.h>
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFloatAttribute.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfIntAttribute.h>
#include <OpenEXR/ImfMultiPartOutputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfOutputPart.h>
#include <OpenEXR/ImfPartType.h>
#include <OpenEXR/ImfStandardAttributes.h>
#include <OpenEXR/ImfStdIO.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <OpenEXR/ImfTiledOutputFile.h>
#include <OpenEXR/ImfTiledOutputPart.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <ctime>
#include <exception>
#include <filesystem>
#include <functional>
#include <limits>
#include <sstream>
#include <system_error>

#include "core/error.h"
#include "io/exr/atomic_write.h"
#include "io/exr/cryptomatte.h"
#include "io/exr/exr_atomic_file.h"
#include "io/exr/exr_base_header.h"
#include "io/exr/exr_checksum.h"
#include "io/exr/exr_header.h"
#include "io/exr/exr_header_copy.h"
#include "io/exr/exr_message.h"
#include "io/exr/exr_threads.h"

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
  Imf::PixelType format;
  // Data layers (depth, positions, ids) are always float and never stored with a lossy codec:
  // distances and positions need the precision, ids must stay exact integers.
  bool data = false;
  std::vector<channel> channels;
};

Imf::PixelType type_of(sample_format format) {
  return format == sample_format::float32 ? Imf::FLOAT : Imf::HALF;
}

// One Cryptomatte layer: ⌈depth/2⌉ RGBA sets named <name>00, <name>01, ..., each holding two
// ranks as (id, coverage, id, coverage); a rank past depth stays 0. Float: the ids are bit patterns.
layer cryptomatte_layer_of(const std::string& name, const std::vector<id_coverage>& ranks, int depth) {
  layer l{name, Imf::FLOAT, true, {}};
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

// Half's largest finite value is 65504: a brighter colour would become +inf in a half channel, and
// the image holds no infinities but background Z, so a half colour layer saturates there instead.
float saturation_of(Imf::PixelType format) {
  return format == Imf::FLOAT ? std::numeric_limits<float>::max() : 65504.0f;
}

std::vector<std::string> words_of(const char* text) {
  std::istringstream in(text);
  std::vector<std::string> out;
  for (std::string word; in >> word;) out.push_back(word);
  return out;
}

// The layers of one AOV of the table (render/aov_table.h) that the film holds: its parts with their
// channels, or one layer per light group or shadow matte. Colour layers take their format from the
// settings and saturate at its range; data layers are float.
void add_aov_layers(const aov_row& row, const film& f, const layer_formats& formats,
                    std::vector<layer>& out) {
  const Imf::PixelType format = row.data ? Imf::FLOAT : type_of(formats[row.id]);
  const float limit = row.data ? std::numeric_limits<float>::max() : saturation_of(format);
  const std::vector<std::string> parts = words_of(row.parts), channels = words_of(row.channels);
  switch (row.shape) {
    case aov_shape::rgba: {
      layer l{parts[0], format, row.data, {}};
      for (int c = 0; c < 4; ++c)
        l.channels.push_back({channels[size_t(c)],
                              [&f, c, limit](size_t i) { return std::clamp(f.color[i][c], -limit, limit); }});
      out.push_back(std::move(l));
      return;
    }
    case aov_shape::scalar:
      out.push_back({parts[0], format, row.data, {{channels[0], [&f](size_t i) { return f.depth[i]; }}}});
      return;
    case aov_shape::triple: {
      layer l{parts[0], format, row.data, {}};
      const std::vector<vec3>& buffer = f.vec3_layer(row.id);
      for (int c = 0; c < 3; ++c)
        l.channels.push_back({channels[size_t(c)], [&buffer, c, limit](size_t i) {
                                return std::clamp(buffer[i][c], -limit, limit);
                              }});
      out.push_back(std::move(l));
      return;
    }
    case aov_shape::pair: {
      layer l{parts[0], format, row.data, {}};
      for (int c = 0; c < 2; ++c)
        l.channels.push_back({channels[size_t(c)], [&f, c](size_t i) { return f.uv[i][c]; }});
      out.push_back(std::move(l));
      return;
    }
    case aov_shape::ids: {
      layer l{parts[0], format, row.data, {}};
      for (int c = 0; c < 3; ++c)
        l.channels.push_back({channels[size_t(c)], [&f, c](size_t i) { return float(f.ids[i][c]); }});
      out.push_back(std::move(l));
      return;
    }
    case aov_shape::motion:
      // Nuke's forward and backward layers (u, v).
      for (size_t p = 0; p < 2; ++p) {
        layer l{parts[p], format, row.data, {}};
        for (size_t c = 0; c < 2; ++c)
          l.channels.push_back(
              {channels[2 * p + c], [&f, index = int(2 * p + c)](size_t i) { return f.motion[i][index]; }});
        out.push_back(std::move(l));
      }
      return;
    case aov_shape::per_group: {
      const size_t groups = size_t(f.light_group_count());
      for (size_t g = 0; g < groups; ++g) {
        const std::string& name = f.light_group_layers[g];
        layer l{name, format, row.data, {}};
        const char* rgb[3] = {".R", ".G", ".B"};
        for (int c = 0; c < 3; ++c)
          l.channels.push_back({name + rgb[c], [&f, groups, g, c, limit](size_t i) {
                                  return std::clamp(f.light_groups[i * groups + g][c], -limit, limit);
                                }});
        out.push_back(std::move(l));
      }
      return;
    }
    case aov_shape::per_matte: {
      const size_t mattes = size_t(f.shadow_count());
      for (size_t g = 0; g < mattes; ++g) {
        const std::string name = f.shadow_layer(int(g));
        layer l{name, format, row.data, {}};
        l.channels.push_back({name + ".A", [&f, mattes, g](size_t i) { return f.shadow[i * mattes + g]; }});
        out.push_back(std::move(l));
      }
      return;
    }
    case aov_shape::ranks:
      out.push_back(
          row.id == aov::crypto_object
              ? cryptomatte_layer_of(crypto_object_layer_name, f.crypto_object, f.aovs.crypto_depth)
              : cryptomatte_layer_of(crypto_material_layer_name, f.crypto_material, f.aovs.crypto_depth));
      return;
  }
}

// The layers of the film's AOVs, in the table's order, Cryptomatte's last.
std::vector<layer> film_layers(const film& f, const exr_settings& settings) {
  std::vector<layer> out;
  for (bool ranks : {false, true})
    for (const aov_row& row : aov_table)
      if ((row.shape == aov_shape::ranks) == ranks && f.aovs.has(row.id))
        add_aov_layers(row, f, settings.formats, out);
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

// The OpenEXR codec of one of exr_compression_names().
Imf::Compression codec_of(const std::string& name) {
  static const std::pair<const char*, Imf::Compression> codecs[] = {
      {"none", Imf::NO_COMPRESSION},  {"rle", Imf::RLE_COMPRESSION},   {"zips", Imf::ZIPS_COMPRESSION},
      {"zip", Imf::ZIP_COMPRESSION},  {"piz", Imf::PIZ_COMPRESSION},   {"pxr24", Imf::PXR24_COMPRESSION},
      {"b44", Imf::B44_COMPRESSION},  {"b44a", Imf::B44A_COMPRESSION}, {"dwaa", Imf::DWAA_COMPRESSION},
      {"dwab", Imf::DWAB_COMPRESSION}};
  for (const auto& [codec_name, codec] : codecs)
    if (name == codec_name) return codec;
  throw input_error("", "--compression", "unknown EXR codec '" + name + "'");
}

// A part's codec: the settings' codec at its level, or zip for a part holding a data layer when
// that codec is lossy. zlib's level lives only in the writer (the file does not record it): 1-9,
// anything else 4, OpenEXR's default. A DWA level is the dwaCompressionLevel attribute (45 by
// default), which the compressor reads and readers show.
void set_compression(Imf::Header& header, const exr_settings& settings, bool data) {
  const int level = settings.compression_level;
  if (data && is_lossy_compression(settings.compression)) {
    header.compression() = Imf::ZIP_COMPRESSION;
    header.zipCompressionLevel() = 4;
    return;
  }
  header.compression() = codec_of(settings.compression);
  if (settings.compression == "zip" || settings.compression == "zips")
    header.zipCompressionLevel() = level >= 1 && level <= 9 ? level : 4;
  if (settings.compression == "dwaa" || settings.compression == "dwab") {
    const float dwa_level = level > 0 ? float(level) : 45.0f;
    header.insert("dwaCompressionLevel", Imf::FloatAttribute(dwa_level));
    header.dwaCompressionLevel() = dwa_level;
  }
}

// The header every part carries: windows, colour space, camera matrices, metadata, tiling.
Imf::Header base_header(const film& f, const exr_settings& settings, const exr_metadata& metadata) {
  // The data window is the stored region; the display window the full frame (they differ for crops).
  Imf::Header header =
      exr_base_header({f.full_width, f.full_height}, {f.x0, f.y0, f.x0 + f.width, f.y0 + f.height}, metadata);
  if (settings.tile_size > 0)
    header.setTileDescription(
        Imf::TileDescription(unsigned(settings.tile_size), unsigned(settings.tile_size)));
  return header;
}

// A part holding layers: the base header with their channels, formats and codec, and with
// --multipart the layer's name (Nuke shows part names as layers).
Imf::Header part_header(Imf::Header header, const std::vector<const layer*>& layers,
                        const exr_settings& settings) {
  bool data = false;
  for (const layer* l : layers) {
    for (const channel& c : l->channels) header.channels().insert(c.name, Imf::Channel(l->format));
    data = data || l->data;
  }
  set_compression(header, settings, data);
  if (layers.size() == 1 && settings.multipart) header.setName(layers.front()->part);
  return header;
}

size_t format_bytes(Imf::PixelType type) { return type == Imf::HALF ? 2 : 4; }

// The frame buffer of one part: its channels' slices of pixels (see write_parts) from byte offset on,
// which moves past them.
Imf::FrameBuffer frame_buffer(const Imf::Header& header, const unsigned char* pixels, size_t pixel,
                              size_t& offset) {
  Imf::FrameBuffer buffer;
  for (auto c = header.channels().begin(); c != header.channels().end(); ++c) {
    buffer.insert(c.name(), Imf::Slice::Make(c.channel().type, pixels + offset, header.dataWindow(), pixel));
    offset += format_bytes(c.channel().type);
  }
  return buffer;
}

// Stops a write between chunks once cancel is raised (a signal): a large file, or one of a million
// tiny tiles, must not keep a signalled process writing for minutes.
void throw_if_cancelled(const std::atomic<bool>* cancel) {
  if (cancel && cancel->load()) throw error(error_kind::interrupted, "", "", "interrupted while writing");
}

// Writes every pixel of a scanline (OutputFile, OutputPart) or tiled (TiledOutputFile,
// TiledOutputPart) file or part: 64 scanlines or one row of tiles at a time.
template <class scanline_output>
void write_lines(scanline_output& out, const Imf::FrameBuffer& buffer, const std::atomic<bool>* cancel) {
  out.setFrameBuffer(buffer);
  const int rows = out.header().dataWindow().max.y - out.header().dataWindow().min.y + 1;
  for (int done = 0; done < rows; done += 64) {
    throw_if_cancelled(cancel);
    out.writePixels(std::min(64, rows - done));
  }
}
template <class tiled_output>
void write_tiles(tiled_output& out, const Imf::FrameBuffer& buffer, const std::atomic<bool>* cancel) {
  out.setFrameBuffer(buffer);
  for (int row = 0; row < out.numYTiles(0); ++row) {
    throw_if_cancelled(cancel);
    out.writeTiles(0, out.numXTiles(0) - 1, row, row);
  }
}

// Writes headers' parts into stream: one makes a single-part file (OpenEXR 1.x layout, no "type"
// attribute), more a multi-part file whose parts each name their type.
void write_file(Imf::OStream& stream, const std::vector<Imf::Header>& headers, const unsigned char* pixels,
                size_t pixel, const std::atomic<bool>* cancel) {
  size_t offset = 0;
  if (headers.size() == 1) {
    // OpenEXR names a single-part file's type when it reads one; the file itself never did.
    Imf::Header header = header_without(headers.front(), "type");
    const Imf::FrameBuffer buffer = frame_buffer(header, pixels, pixel, offset);
    if (header.hasTileDescription()) {
      Imf::TiledOutputFile out(stream, header);
      write_tiles(out, buffer, cancel);
    } else {
      Imf::OutputFile out(stream, header);
      write_lines(out, buffer, cancel);
    }
    return;
  }
  std::vector<Imf::Header> typed = headers;
  for (Imf::Header& header : typed)
    header.setType(header.hasTileDescription() ? Imf::TILEDIMAGE : Imf::SCANLINEIMAGE);
  Imf::MultiPartOutputFile file(stream, typed.data(), int(typed.size()));
  for (int part = 0; part < int(typed.size()); ++part) {
    const Imf::FrameBuffer buffer = frame_buffer(typed[size_t(part)], pixels, pixel, offset);
    if (typed[size_t(part)].hasTileDescription()) {
      Imf::TiledOutputPart out(file, part);
      write_tiles(out, buffer, cancel);
    } else {
      Imf::OutputPart out(file, part);
      write_lines(out, buffer, cancel);
    }
  }
}

bool lossy(Imf::Compression codec) {
  switch (codec) {
    case Imf::PXR24_COMPRESSION:
    case Imf::B44_COMPRESSION:
    case Imf::B44A_COMPRESSION:
    case Imf::DWAA_COMPRESSION:
    case Imf::DWAB_COMPRESSION:
      return true;
    default:
      return false;
  }
}

// The checksum of the pixels a reader of the file will get back (io/exr/exr_checksum.h). Lossless
// codecs give back these very bytes; a lossy codec's values are known only after it has run, so the
// file is encoded once in memory and decoded again (about the file's size in memory, plus the decode).
std::string stored_checksum(const std::vector<Imf::Header>& headers, const unsigned char* pixels,
                            size_t pixel, const std::atomic<bool>* cancel) {
  const Imath::Box2i& w = headers.front().dataWindow();
  const size_t bytes = size_t(w.max.x - w.min.x + 1) * size_t(w.max.y - w.min.y + 1) * pixel;
  if (std::none_of(headers.begin(), headers.end(),
                   [](const Imf::Header& h) { return lossy(h.compression()); }))
    return flat_exr_checksum(headers, pixels, bytes);
  Imf::StdOSStream encoded;
  write_file(encoded, headers, pixels, pixel, cancel);
  Imf::StdISStream decoded;
  decoded.str(encoded.str());
  Imf::MultiPartInputFile file(decoded);
  return flat_exr_checksum(file, "", nullptr);
}

// Writes headers as the parts of one file at path, atomically, each with kiln/checksum. pixels holds
// every part's channels interleaved, `pixel` bytes a pixel, row-major over the parts' (common) data
// window: the parts one after another, each part's channels in its channel list's order and in their
// own formats.
void write_parts(const std::string& path, std::vector<Imf::Header> headers, const unsigned char* pixels,
                 size_t pixel, const std::atomic<bool>* cancel = nullptr) {
  std::string checksum;
  try {
    checksum = stored_checksum(headers, pixels, pixel, cancel);
  } catch (const error& e) {
    if (e.kind() == error_kind::interrupted) throw error(error_kind::interrupted, path, "", e.what());
    throw io_error(path, std::string("cannot write EXR: ") + e.what());
  } catch (const std::exception& e) {
    throw io_error(path, "cannot write EXR: " + exr_message(e.what(), path));
  }
  for (Imf::Header& header : headers) {
    // A copied header (write_exr of an image read back) holds its source's.
    if (header.find(exr_checksum_attribute) != header.end())
      header = header_without(header, exr_checksum_attribute);
    header.insert(exr_checksum_attribute, Imf::StringAttribute(checksum));
  }
  write_exr_atomically(
      path, "EXR", [&](Imf::OStream& stream) { write_file(stream, headers, pixels, pixel, cancel); }, cancel);
}

// The bytes a pixel of headers' channels takes, in their formats.
size_t pixel_bytes_of(const std::vector<Imf::Header>& headers) {
  size_t bytes = 0;
  for (const Imf::Header& header : headers)
    for (auto c = header.channels().begin(); c != header.channels().end(); ++c)
      bytes += format_bytes(c.channel().type);
  return bytes;
}

// One layer's samples as the file stores them: rounded to half where the layer is half.
stored_layer stored(const layer& l, size_t pixels) {
  stored_layer s{l.part, {}, l.format == Imf::HALF, {}};
  s.samples.resize(pixels * l.channels.size());
  for (const channel& c : l.channels) s.channels.push_back(c.name);
  for (size_t i = 0; i < pixels; ++i)
    for (size_t c = 0; c < l.channels.size(); ++c) {
      const float value = l.channels[c].value(i);
      s.samples[i * l.channels.size() + c] = s.half ? float(half(value)) : value;
    }
  return s;
}

}  // namespace

std::vector<stored_layer> stored_layers(const film& f, const exr_settings& settings) {
  std::vector<stored_layer> out;
  for (const layer& l : film_layers(f, settings))
    out.push_back(stored(l, size_t(f.width) * size_t(f.height)));
  return out;
}

std::optional<rgba_image> stored_beauty(const film& f, const exr_settings& settings) {
  if (is_lossy_compression(settings.compression)) return std::nullopt;
  for (const layer& l : film_layers(f, settings))
    if (l.part == aov_row_of(aov::beauty).parts) {  // R, G, B, A in that order
      rgba_image beauty;
      beauty.width = f.width;
      beauty.height = f.height;
      beauty.pixels = stored(l, size_t(f.width) * size_t(f.height)).samples;
      return beauty;
    }
  return std::nullopt;
}

void check_output_writable(const std::string& path, bool probe_folder) {
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
  if (!probe_folder) return;
  // access() answers yes to root for any folder, including /proc and /sys where nothing can be
  // created, so create a temporary file as the writer will, and remove it again.
  std::string probe;
  const int fd = create_temporary_file(path, probe);
  if (fd < 0)
    throw io_error(path,
                   "output folder is not writable: " + folder.string() + " (" + std::strerror(errno) + ")");
  ::close(fd);
  ::unlink(probe.c_str());
}

void check_exr_settings(const aov_set& aovs, const exr_settings& settings) {
  film shape;  // no pixels: only which layers exist matters
  shape.aovs = aovs;
  check_layers(film_layers(shape, settings), settings);
}

void write_exr(const std::string& path, const film& f, const exr_settings& settings,
               const exr_metadata& metadata, const std::atomic<bool>* cancel) {
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
  std::vector<Imf::Header> headers;
  try {
    const Imf::Header base = base_header(f, settings, metadata);
    for (const auto& part : parts) headers.push_back(part_header(base, part, settings));
  } catch (const error&) {
    throw;
  } catch (const std::exception& e) {  // e.g. a metadata key that is a standard attribute of another type
    throw io_error(path, "cannot write EXR: " + exr_message(e.what(), path));
  }
  // The film's values in the file's layout: per part, its channels in channel-list order, half
  // channels rounded here (to nearest even, as OpenEXR itself would).
  struct source {
    const channel* values;
    Imf::PixelType type;
  };
  std::vector<source> sources;
  for (size_t p = 0; p < parts.size(); ++p)
    for (auto c = headers[p].channels().begin(); c != headers[p].channels().end(); ++c)
      for (const layer* l : parts[p])
        for (const channel& ch : l->channels)
          if (ch.name == c.name()) sources.push_back({&ch, l->format});
  const size_t pixel = pixel_bytes_of(headers);
  const size_t count = size_t(f.width) * size_t(f.height);
  std::vector<unsigned char> pixels(count * pixel);
  for (size_t i = 0; i < count; ++i) {
    unsigned char* out = pixels.data() + i * pixel;
    for (const source& s : sources) {
      const float value = s.values->value(i);
      if (s.type == Imf::HALF) {
        const uint16_t bits = half(value).bits();
        std::memcpy(out, &bits, sizeof bits);
        out += sizeof bits;
      } else {
        std::memcpy(out, &value, sizeof value);
        out += sizeof value;
      }
    }
  }
  write_parts(path, headers, pixels.data(), pixel, cancel);
}

void write_exr(const std::string& path, const exr_image& image) {
  check_output_writable(path);
  const pixel_rect& d = image.data_window;
  if (!image.header || image.header->parts.empty() || d.width() <= 0 || d.height() <= 0 ||
      image.pixels.size() != size_t(d.width()) * size_t(d.height()) * image.pixel_bytes())
    throw io_error(path, "refusing to write an empty or inconsistent image");
  std::vector<Imf::Header> headers;
  for (const Imf::Header& source : image.header->parts) {
    // Every attribute but the chunk count of the source's data window (OpenEXR counts it again
    // for a multi-part file).
    headers.push_back(header_without(source, "chunkCount"));
  }
  for (Imf::Header& header : headers) {
    header.dataWindow() = Imath::Box2i(Imath::V2i(d.x0, d.y0), Imath::V2i(d.x1 - 1, d.y1 - 1));
    // OpenEXR reads a DWA level into the attribute only; its compressor takes the header's field.
    if (const auto* level = header.findTypedAttribute<Imf::FloatAttribute>("dwaCompressionLevel"))
      header.dwaCompressionLevel() = level->value();
  }
  if (pixel_bytes_of(headers) != image.pixel_bytes())
    throw io_error(path, "refusing to write an inconsistent image");
  write_parts(path, headers, image.pixels.data(), image.pixel_bytes());
}

}  // namespace kiln
