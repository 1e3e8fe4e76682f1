#include "io/exr/exr_writer.h"

#include "core/error.h"

#include <OpenImageIO/imageio.h>

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <limits>
#include <system_error>

namespace kiln {
namespace fs = std::filesystem;

namespace {

constexpr int channel_count = 8;  // R G B A Z N.X N.Y N.Z

// Temporary name beside the target, so the final rename stays on one file system.
std::string temporary_path(const std::string& path) {
  fs::path target(path);
  std::string name = "." + target.filename().string() + ".tmp-" + std::to_string(::getpid());
  return (target.parent_path() / name).string();
}

OIIO::ImageSpec make_spec(const film& f, const exr_settings& settings, const exr_metadata& metadata) {
  OIIO::ImageSpec spec(f.width, f.height, channel_count, OIIO::TypeDesc::FLOAT);
  spec.channelnames = {"R", "G", "B", "A", "Z", "N.X", "N.Y", "N.Z"};
  spec.alpha_channel = 3;
  spec.z_channel = 4;
  OIIO::TypeDesc colour = settings.full_float ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::HALF;
  spec.channelformats = {colour, colour, colour, colour, OIIO::TypeDesc::FLOAT, colour, colour, colour};
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
  return spec;
}

// Half's largest finite value. A brighter float would become +inf in a half channel, and the
// image holds no infinities but background Z, so half colour saturates here instead.
constexpr float half_max = 65504.0f;

std::vector<float> interleave(const film& f, bool full_float) {
  std::vector<float> pixels(size_t(f.width) * f.height * channel_count);
  const float limit = full_float ? std::numeric_limits<float>::max() : half_max;
  for (size_t i = 0; i < size_t(f.width) * f.height; ++i) {
    float* p = &pixels[i * channel_count];
    for (int c = 0; c < 4; ++c) p[c] = std::clamp(f.color[i][c], -limit, limit);
    p[4] = f.depth[i];
    for (int c = 0; c < 3; ++c) p[5 + c] = f.normal[i][c];
  }
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
  const std::string temporary = temporary_path(path);
  auto out = OIIO::ImageOutput::create("openexr");
  if (!out) throw io_error(path, "OpenImageIO has no OpenEXR writer: " + OIIO::geterror());
  OIIO::ImageSpec spec = make_spec(f, settings, metadata);
  std::vector<float> pixels = interleave(f, settings.full_float);
  bool ok = out->open(temporary, spec) && out->write_image(OIIO::TypeDesc::FLOAT, pixels.data());
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

}  // namespace kiln
