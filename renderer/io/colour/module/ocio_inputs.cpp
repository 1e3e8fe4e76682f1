// The config is read by kiln (io/file's checked reader) and its bytes handed to OpenColorIO, so
// what OpenColorIO parses is what was checked. A FileTransform's file is found as OpenColorIO
// finds it (the config's context: search path, working folder, context variables), and checked
// with the rules an asset's URIs get; OpenColorIO opens it later by path, so a file swapped for a
// FIFO in between is not caught (nor is it for any library that opens its own files).
#include "io/colour/module/ocio_inputs.h"

#include <sys/stat.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>
#include <sstream>
#include <string>

#include "core/error.h"
#include "core/message_text.h"
#include "io/colour/module/ocio_config_text.h"
#include "io/file/input_file.h"

namespace OCIO = OCIO_NAMESPACE;

namespace kiln::colour_module {
namespace {

std::string number_text(double v) {
  std::ostringstream text;
  text << v;
  return text.str();
}

// Follows GroupTransforms to the FileTransforms and MatrixTransforms of the transforms a
// processor may use; a file is checked once however many transforms name it.
class input_check {
 public:
  input_check(const OCIO::Config& cfg, const colour_config_source& config)
      : context_(cfg.getCurrentContext()), config_(config) {}

  void transform(const OCIO::ConstTransformRcPtr& t, const std::string& where) {
    if (const auto group = OCIO::DynamicPtrCast<const OCIO::GroupTransform>(t)) {
      for (int i = 0; i < group->getNumTransforms(); ++i) transform(group->getTransform(i), where);
    } else if (const auto file = OCIO::DynamicPtrCast<const OCIO::FileTransform>(t)) {
      check_file(*file, where);
    } else if (const auto matrix = OCIO::DynamicPtrCast<const OCIO::MatrixTransform>(t)) {
      check_matrix(*matrix, where);
    }
  }

 private:
  void check_file(const OCIO::FileTransform& ft, const std::string& where) {
    const std::string src = ft.getSrc() ? ft.getSrc() : "";
    if (src.empty()) return;
    std::string path;
    try {
      path = context_->resolveFileLocation(src.c_str());
    } catch (const OCIO::Exception&) {
      return;  // not found: OpenColorIO says so, with the places it looked
    }
    if (!checked_.insert(path).second) return;
    const std::string named =
        "its FileTransform " + quoted(src) + (path == src ? "" : " (" + shown(path) + ")");
    if (const std::string why = input_file_problem(path, max_lut_bytes); !why.empty())
      throw refused(where, named + " " + why);
    struct stat info {};
    if (::stat(path.c_str(), &info) == 0) total_ += uint64_t(info.st_size);
    if (total_ > max_lut_bytes)
      throw refused(where, named + " brings the files kiln's conversion reads to " + std::to_string(total_) +
                               " bytes, over kiln's limit of " + std::to_string(max_lut_bytes));
    // A CTF or CLF file's <Reference> elements name further files, which OpenColorIO would open
    // unchecked; OpenColorIO may read any file as CTF when its own format fails, so all are looked at.
    const std::string element = "<Reference";
    std::string window;
    bool refers = false;
    read_input_file(path, input_file_request(max_lut_bytes, nullptr, config_.path, where),
                    [&](const char* bytes, size_t count) {
                      window.append(bytes, count);
                      refers = refers || window.find(element) != std::string::npos;
                      window.erase(0, window.size() - std::min(window.size(), element.size() - 1));
                    });
    if (refers)
      throw refused(where, named + " refers to other files (a CTF <Reference>), which kiln does not follow");
  }

  void check_matrix(const OCIO::MatrixTransform& mt, const std::string& where) {
    double matrix[16], offset[4];
    mt.getMatrix(matrix);
    mt.getOffset(offset);
    for (int i = 0; i < 20; ++i) {
      const double v = i < 16 ? matrix[i] : offset[i - 16];
      if (!std::isfinite(v))
        throw refused(where, "its MatrixTransform holds " + number_text(v) + " (" +
                                 (i < 16 ? "matrix value " + std::to_string(i + 1) + " of 16"
                                         : "offset value " + std::to_string(i - 15) + " of 4") +
                                 "); kiln converts colours only through finite numbers");
    }
  }

  error refused(const std::string& where, const std::string& why) const {
    return input_error(config_.path, where, why + " (config from " + config_.named_by + ")");
  }

  OCIO::ConstContextRcPtr context_;
  const colour_config_source& config_;
  std::set<std::string> checked_;
  uint64_t total_ = 0;
};

}  // namespace

OCIO::ConstConfigRcPtr read_checked_config(const colour_config_source& config) {
  if (input_file_missing(config.path))
    throw input_error(config.path, config.named_by, "no such OpenColorIO config file");
  const std::vector<uint8_t> bytes = read_whole_input_file(
      config.path, input_file_request(max_colour_config_bytes, nullptr, config.path, config.named_by));
  const std::string text(bytes.begin(), bytes.end());
  const config_text_shape shape = scan_config_text(text);
  if (!shape.refusal.empty())
    throw input_error(config.path, config.named_by,
                      shape.refusal +
                          ": kiln reads OpenColorIO configs without YAML anchors, aliases, %TAG directives, "
                          "explicit keys or tab indentation, which its count of entries cannot follow");
  if (shape.entries > max_config_entries)
    throw input_error(config.path, config.named_by,
                      "lists " + std::to_string(shape.entries) + " entries (" +
                          std::to_string(shape.colour_spaces) +
                          " colour spaces; aliases, roles, displays, views, looks, transforms in lists and "
                          "rules count too), over kiln's limit of " +
                          std::to_string(max_config_entries) +
                          ": OpenColorIO's time to read a config grows with their square");
  std::istringstream stream(text);
  const OCIO::ConfigRcPtr cfg = OCIO::Config::CreateFromStream(stream)->createEditableCopy();
  if (cfg->getNumSearchPaths() > max_search_paths)
    throw input_error(config.path, config.named_by,
                      "names " + std::to_string(cfg->getNumSearchPaths()) +
                          " search paths, over kiln's limit of " + std::to_string(max_search_paths) +
                          ": each file it names is looked for along every one");
  // Relative search paths start from the config's folder, as CreateFromFile sets it.
  std::error_code ec;
  const std::filesystem::path absolute = std::filesystem::absolute(config.path, ec).lexically_normal();
  cfg->setWorkingDir(absolute.parent_path().string().c_str());
  return cfg;
}

void check_transform_inputs(const OCIO::Config& cfg, const std::vector<held_transform>& transforms,
                            const colour_config_source& config) {
  input_check check(cfg, config);
  for (const held_transform& h : transforms) check.transform(h.transform, h.where);
}

}  // namespace kiln::colour_module
