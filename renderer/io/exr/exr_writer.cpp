#include "io/exr/exr_writer.h"

#include "core/error.h"
#include "io/exr/exr_header.h"

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
#include "io/exr/cryptomatte.h"
#include "io/exr/exr_header.h"

namespace kiln {
namespace fs = std::filesystem;

namespace {

// One channel of the file: its name, its pixel format and where its values come from.
struct channel {
  std::string name;
  OIIO::TypeDesc format;
  std::function<float(size_t)> value;
};

// One Cryptomatte layer: ⌈depth/2⌉ RGBA sets named <layer>00, <layer>01, ..., each holding two
// ranks as (id, coverage, id, coverage); a rank past depth stays 0. Float: the ids are bit patterns.
void add_cryptomatte_channels(std::vector<channel>& out, const std::string& layer,
                              const std::vector<id_coverage>& ranks, int depth) {
  const char* rgba[4] = {".R", ".G", ".B", ".A"};
  for (int set = 0; 2 * set < depth; ++set) {
    const std::string number = (set < 10 ? "0" : "") + std::to_string(set);
    for (int c = 0; c < 4; ++c) {
      const int rank = 2 * set + c / 2;
      const bool id = c % 2 == 0;
      out.push_back({layer + number + rgba[c], OIIO::TypeDesc::FLOAT, [&ranks, depth, rank, id](size_t i) {
                       if (rank >= depth) return 0.0f;
                       const id_coverage& r = ranks[i * size_t(depth) + size_t(rank)];
                       if (!id) return r.coverage;
                       float value;
                       std::memcpy(&value, &r.id, sizeof value);
                       return value;
                     }});
    }
  }
}

// The channels of the film's AOVs, in the order of aov_list_name(). Z, P and the ids are always
// float (distances and positions need the precision; ids must stay exact integers).
std::vector<channel> film_channels(const film& f, const exr_settings& settings) {
  const OIIO::TypeDesc small = settings.full_float ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::HALF;
  const OIIO::TypeDesc full = OIIO::TypeDesc::FLOAT;
  std::vector<channel> out;
  auto add = [&out](const std::string& name, OIIO::TypeDesc format, std::function<float(size_t)> value) {
    out.push_back({name, format, std::move(value)});
  };
  const aov_set& a = f.aovs;
  const char* rgba[4] = {"R", "G", "B", "A"};
  const char* xyz[3] = {".X", ".Y", ".Z"};
  const char* rgb[3] = {".R", ".G", ".B"};
  // Half's largest finite value is 65504: a brighter colour would become +inf in a half channel,
  // and the image holds no infinities but background Z, so half colour saturates there instead.
  const float limit = settings.full_float ? std::numeric_limits<float>::max() : 65504.0f;
  for (int c = 0; c < 4 && a.beauty; ++c)
    add(rgba[c], small, [&f, c, limit](size_t i) { return std::clamp(f.color[i][c], -limit, limit); });
  if (a.depth) add("Z", full, [&f](size_t i) { return f.depth[i]; });
  for (int c = 0; c < 3 && a.normal; ++c)
    add(std::string("N") + xyz[c], small, [&f, c](size_t i) { return f.normal[i][c]; });
  for (int c = 0; c < 3 && a.position; ++c)
    add(std::string("P") + xyz[c], full, [&f, c](size_t i) { return f.position[i][c]; });
  for (int c = 0; c < 3 && a.albedo; ++c)
    add(std::string("albedo") + rgb[c], small, [&f, c](size_t i) { return f.albedo[i][c]; });
  if (a.uv) {
    add("uv.U", small, [&f](size_t i) { return f.uv[i].x; });
    add("uv.V", small, [&f](size_t i) { return f.uv[i].y; });
  }
  const char* id_names[3] = {"id.object", "id.material", "id.instance"};
  for (int c = 0; c < 3 && a.ids; ++c)
    add(id_names[c], full, [&f, c](size_t i) { return float(f.ids[i][c]); });
  // The light split: colour like R G B (half unless --float, saturating like it).
  const std::pair<bool, const std::vector<vec3>*> parts[3] = {
      {a.direct, &f.direct}, {a.reflection, &f.reflection}, {a.refraction, &f.refraction}};
  const char* part_names[3] = {"direct", "reflection", "refraction"};
  for (int p = 0; p < 3; ++p)
    for (int c = 0; c < 3 && parts[p].first; ++c)
      add(std::string(part_names[p]) + rgb[c], small, [buffer = parts[p].second, c, limit](size_t i) {
        return std::clamp((*buffer)[i][c], -limit, limit);
      });
  if (a.crypto_object)
    add_cryptomatte_channels(out, crypto_object_layer_name, f.crypto_object, a.crypto_depth);
  if (a.crypto_material)
    add_cryptomatte_channels(out, crypto_material_layer_name, f.crypto_material, a.crypto_depth);
  return out;
}

// Temporary name beside the target, so the final rename stays on one file system.
std::string temporary_path(const std::string& path) {
  fs::path target(path);
  std::string name = "." + target.filename().string() + ".tmp-" + std::to_string(::getpid());
  return (target.parent_path() / name).string();
}

OIIO::ImageSpec make_spec(const film& f, const std::vector<channel>& channels, const exr_metadata& metadata) {
  OIIO::ImageSpec spec(f.width, f.height, int(channels.size()), OIIO::TypeDesc::FLOAT);
  // The data window is the stored region; the display window the full frame (they differ for crops).
  spec.x = f.x0;
  spec.y = f.y0;
  spec.full_x = 0;
  spec.full_y = 0;
  spec.full_width = f.full_width;
  spec.full_height = f.full_height;
  spec.channelnames.clear();
  for (const channel& c : channels) {
    spec.channelnames.push_back(c.name);
    spec.channelformats.push_back(c.format);
  }
  spec.alpha_channel = f.aovs.beauty ? 3 : -1;
  spec.z_channel = f.aovs.depth ? (f.aovs.beauty ? 4 : 0) : -1;
  spec.attribute("compression", "zip");
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

std::vector<float> interleave(const film& f, const std::vector<channel>& channels) {
  const size_t n = channels.size();
  std::vector<float> pixels(size_t(f.width) * f.height * n);
  for (size_t i = 0; i < size_t(f.width) * f.height; ++i)
    for (size_t c = 0; c < n; ++c) pixels[i * n + c] = channels[c].value(i);
  return pixels;
}

// Flushes a closed file's data to the disk. OpenImageIO does not expose its descriptor, so the
// file is opened again: fsync on any descriptor of the file syncs its data. Without this a crash
// right after the rename can leave the target name pointing at an empty or partial file.
bool sync_to_disk(const std::string& path, int flags) {
  const int fd = ::open(path.c_str(), flags | O_CLOEXEC);
  if (fd < 0) return false;
  const bool ok = ::fsync(fd) == 0;
  return ::close(fd) == 0 && ok;
}

// Writes spec and pixels (in format) to a temporary file beside path, flushes it and renames it
// into place. Throws kiln::error (io) on failure, leaving no temporary behind.
void write_atomically(const std::string& path, const OIIO::ImageSpec& spec, OIIO::TypeDesc format,
                      const void* pixels) {
  const std::string temporary = temporary_path(path);
  auto out = OIIO::ImageOutput::create("openexr");
  if (!out) throw io_error(path, "OpenImageIO has no OpenEXR writer: " + OIIO::geterror());
  bool ok = out->open(temporary, spec) && out->write_image(format, pixels);
  ok = out->close() && ok;
  std::string reason = ok ? std::string() : out->geterror();
  if (ok && !sync_to_disk(temporary, O_RDONLY)) {
    ok = false;
    reason = "cannot flush the file to disk";
  }
  std::error_code ec;
  if (ok) fs::rename(temporary, path, ec);
  // The rename itself lives in the folder: sync it too, best effort (some file systems refuse).
  if (ok && !ec)
    sync_to_disk(fs::path(path).parent_path().empty() ? "." : fs::path(path).parent_path().string(),
                 O_RDONLY | O_DIRECTORY);
  if (!ok || ec) {
    fs::remove(temporary, ec);
    throw io_error(path, "cannot write EXR: " + (reason.empty() ? std::string("rename failed") : reason));
  }
}

}  // namespace

void check_output_writable(const std::string& path) {
  fs::path target(path);
  if (target.filename().empty()) throw io_error(path, "output path names a folder, not a file");
  fs::path folder = target.parent_path().empty() ? fs::path(".") : target.parent_path();
  std::error_code ec;
  if (!fs::is_directory(folder, ec)) throw io_error(path, "output folder does not exist: " + folder.string());
  if (::access(folder.c_str(), W_OK) != 0) throw io_error(path, "output folder is not writable: " + folder.string());
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

void write_exr(const std::string& path, const film& f, const exr_settings& settings,
               const exr_metadata& metadata) {
  check_output_writable(path);
  if (f.width <= 0 || f.height <= 0 || f.color.size() != size_t(f.width) * f.height)
    throw io_error(path, "refusing to write an empty or inconsistent image");
  const std::vector<channel> channels = film_channels(f, settings);
  if (channels.empty()) throw io_error(path, "refusing to write an image without channels");
  std::vector<float> pixels = interleave(f, channels);
  write_atomically(path, make_spec(f, channels, metadata), OIIO::TypeDesc::FLOAT, pixels.data());
}

void write_exr(const std::string& path, const exr_image& image) {
  check_output_writable(path);
  const pixel_rect& d = image.data_window;
  if (!image.header || d.width() <= 0 || d.height() <= 0 ||
      image.pixels.size() != size_t(d.width()) * size_t(d.height()) * image.pixel_bytes())
    throw io_error(path, "refusing to write an empty or inconsistent image");
  OIIO::ImageSpec spec = image.header->spec;
  spec.x = d.x0;
  spec.y = d.y0;
  spec.width = d.width();
  spec.height = d.height();
  // TypeUnknown: the pixels are in the spec's own per-channel formats.
  write_atomically(path, spec, OIIO::TypeUnknown, image.pixels.data());
}

}  // namespace kiln
