#include "io/gltf/gltf_parse.h"

#include "core/error.h"
#include "io/gltf/glb_container.h"
#include "io/gltf/gltf_common.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <system_error>

namespace kiln::gltf_internal {
namespace {

namespace fs = std::filesystem;

// What the tinygltf file-system callbacks may touch: files inside the asset's folder only.
struct fs_context {
  std::string folder_prefix;  // absolute asset folder, ending in '/'
};

bool read_file_bytes(const std::string& path, std::vector<uint8_t>& out, std::string& why) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) {
    why = "cannot open file";
    return false;
  }
  const uintmax_t size = fs::file_size(path, ec);
  if (ec) {
    why = "cannot open file";
    return false;
  }
  if (size > max_file_bytes) {
    why =
        "file is " + std::to_string(size) + " bytes, over kiln's limit of " + std::to_string(max_file_bytes);
    return false;
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    why = "cannot open file";
    return false;
  }
  out.resize(static_cast<size_t>(size));
  if (size > 0 && !in.read(reinterpret_cast<char*>(out.data()), static_cast<std::streamsize>(size))) {
    why = "cannot read file";
    return false;
  }
  return true;
}

// tinygltf also searches the current directory after the asset folder; joined with "." those
// paths are relative, so accepting only paths under the (absolute) asset folder disables that.
bool file_exists(const std::string& path, void* user) {
  const auto* context = static_cast<const fs_context*>(user);
  if (path.compare(0, context->folder_prefix.size(), context->folder_prefix) != 0) return false;
  std::error_code ec;
  return fs::is_regular_file(path, ec);
}

// The default expands the path with wordexp(), which runs shell expansion on text from the file.
std::string expand_file_path(const std::string& path, void*) { return path; }

bool read_whole_file(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
  if (!file_exists(path, user)) {
    if (err) *err += "not found: " + path + "\n";
    return false;
  }
  std::string why;
  if (!read_file_bytes(path, *out, why)) {
    if (err) *err += why + ": " + path + "\n";
    return false;
  }
  return true;
}

bool write_whole_file(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err) *err += "kiln's glTF loader never writes files\n";
  return false;
}

// Keeps encoded image bytes so that only images a used material references get decoded (by
// OpenImageIO, later). For an image in a bufferView, tinygltf hands over a pointer it never
// bounds-checked against the buffer, so those bytes are not touched here.
bool keep_encoded_image(tinygltf::Image* image, const int, std::string*, std::string*, int, int,
                        const unsigned char* bytes, int size, void*) {
  image->as_is = true;
  if (image->bufferView >= 0) return true;
  if (bytes != nullptr && size > 0) image->image.assign(bytes, bytes + size);
  return true;
}

std::string first_line(const std::string& text) {
  size_t start = 0;
  while (start < text.size()) {
    size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    std::string line = text.substr(start, end - start);
    while (!line.empty() && std::isspace(static_cast<unsigned char>(line.back()))) line.pop_back();
    if (!line.empty()) return line;
    start = end + 1;
  }
  return "";
}

bool has_utf8_bom(const uint8_t* data, size_t size) {
  return size >= 3 && data[0] == 0xEF && data[1] == 0xBB && data[2] == 0xBF;
}

bool ends_with_glb(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext == ".glb";
}

void check_version(const tinygltf::Model& model, const std::string& path) {
  const std::string& version = model.asset.version;
  const std::string major = version.substr(0, version.find('.'));
  if (major != "2")
    throw input_error(path, "/asset/version",
                      "glTF version '" + version + "' is not supported (kiln reads glTF 2.x)");
}

void check_required_extensions(const std::vector<std::string>& required, const std::string& path) {
  const auto& supported = supported_extensions();
  for (size_t i = 0; i < required.size(); ++i) {
    const std::string& name = required[i];
    if (std::find(supported.begin(), supported.end(), name) == supported.end())
      throw input_error(path, pointer_join("/extensionsRequired", static_cast<int64_t>(i)),
                        "required extension " + name + " is not supported");
  }
}

// When tinygltf refuses a file, an unsupported required extension is usually the real cause
// (Draco primitives have accessors without bufferViews, which tinygltf rejects on its own), so
// look for one in the raw JSON and report it instead of tinygltf's symptom.
void check_required_extensions_in_json(const uint8_t* text, size_t size, const std::string& path) {
  const nlohmann::json doc = nlohmann::json::parse(text, text + size, nullptr, /*allow_exceptions=*/false);
  if (!doc.is_object()) return;
  auto required = doc.find("extensionsRequired");
  if (required == doc.end() || !required->is_array()) return;
  std::vector<std::string> names;
  for (const auto& name : *required)
    names.push_back(name.is_string() ? name.get<std::string>() : name.dump());
  check_required_extensions(names, path);
}

}  // namespace

const std::vector<std::string>& supported_extensions() {
  static const std::vector<std::string> names = {
      "KHR_lights_punctual",        "KHR_materials_emissive_strength", "KHR_materials_ior", "KHR_materials_specular",
      "KHR_materials_transmission", "KHR_materials_volume", "KHR_texture_transform",
      "KHR_materials_unlit"};
  return names;
}

tinygltf::Model parse_gltf_file(const std::string& path) {
  std::vector<uint8_t> bytes;
  std::string why;
  if (!read_file_bytes(path, bytes, why)) throw input_error(path, "", why);

  std::error_code ec;
  fs::path folder = fs::absolute(fs::path(path), ec).parent_path();
  if (ec) throw input_error(path, "", "cannot resolve the asset's folder: " + ec.message());
  fs_context context;
  context.folder_prefix = folder.string();
  if (context.folder_prefix.empty() || context.folder_prefix.back() != '/') context.folder_prefix += '/';

  tinygltf::TinyGLTF parser;
  parser.SetFsCallbacks(
      tinygltf::FsCallbacks{&file_exists, &expand_file_path, &read_whole_file, &write_whole_file, &context});
  parser.SetImageLoader(&keep_encoded_image, nullptr);

  tinygltf::Model model;
  std::string err;
  std::string warn;
  bool ok = false;
  size_t json_offset = 0;
  size_t json_length = bytes.size();
  try {
    if (ends_with_glb(path) || has_glb_magic(bytes)) {
      const glb_layout layout = check_glb_container(bytes, path);
      json_offset = layout.json_offset;
      json_length = layout.json_length;
      if (has_utf8_bom(bytes.data() + layout.json_offset, layout.json_length))
        throw input_error(path, "", "GLB JSON chunk starts with a byte order mark, which glTF forbids");
      ok = parser.LoadBinaryFromMemory(&model, &err, &warn, bytes.data(),
                                       static_cast<unsigned int>(bytes.size()), folder.string());
    } else {
      if (has_utf8_bom(bytes.data(), bytes.size()))
        throw input_error(path, "", "JSON starts with a byte order mark, which glTF forbids");
      ok = parser.LoadASCIIFromString(&model, &err, &warn, reinterpret_cast<const char*>(bytes.data()),
                                      static_cast<unsigned int>(bytes.size()), folder.string());
    }
  } catch (const kiln::error&) {
    throw;
  } catch (const std::exception& e) {
    throw input_error(path, "", std::string("invalid glTF: ") + e.what());
  }
  if (!ok) {
    check_required_extensions_in_json(bytes.data() + json_offset, json_length, path);
    std::string line = first_line(err);
    if (line.empty()) line = "tinygltf could not parse the file";
    throw input_error(path, "", "invalid glTF: " + line);
  }
  check_version(model, path);
  check_required_extensions(model.extensionsRequired, path);
  return model;
}

}  // namespace kiln::gltf_internal
