#include "io/gltf/gltf_parse.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <system_error>

#include "core/error.h"
#include "core/message_text.h"
#include "io/file/input_file.h"
#include "io/gltf/glb_container.h"
#include "io/gltf/gltf_common.h"
#include "io/gltf/gltf_compressed_json.h"
#include "io/gltf/gltf_image_use.h"
#include "io/gltf/gltf_memory.h"
#include "io/gltf/gltf_precheck.h"
#include "io/gltf/gltf_schema_check.h"
#include "io/gltf/gltf_uri_files.h"

namespace kiln::gltf_internal {
namespace {

namespace fs = std::filesystem;

// What the tinygltf file-system callbacks may touch: files inside the asset's folder only,
// unless the caller allows files anywhere.
struct fs_context {
  uri_rules rules;
  const std::atomic<bool>* cancel = nullptr;  // raised by SIGINT/SIGTERM: reading stops
  std::string interrupted_file;               // a read it stopped (tinygltf only sees "failed")
  // Filled by the JSON pre-pass: images no material samples are neither read nor kept, so a
  // large unused image file costs no memory (a missing one is still refused, by the pre-pass).
  std::vector<bool> image_used;                  // by image index
  std::set<std::string> unused_image_files;      // canonical paths only unused images name
  memory_charge* memory = nullptr;               // the JSON's parse and the buffers are charged here
  const gltf_memory_asset* in_memory = nullptr;  // an asset in memory: its files, not the folder's
};

// The file an in-memory asset supplies for a path tinygltf asks for: the URI as written, or as
// tinygltf decodes it (percent escapes); null when it is not supplied.
const std::vector<uint8_t>* supplied_file(const gltf_memory_asset& asset, const std::string& path) {
  if (const auto it = asset.files.find(path); it != asset.files.end()) return &it->second;
  for (const auto& [uri, bytes] : asset.files)
    if (percent_decoded(uri) == path) return &bytes;
  return nullptr;
}

// Reads a file the asset names or the asset itself: a regular file within kiln's size limit
// (never a FIFO or a device, which would block or never end), stopping when cancel is raised.
// For tinygltf's file callback, which cannot take an exception: reports failure in why, and an
// interrupt by naming the file in interrupted_file.
bool read_file_bytes(const std::string& path, std::vector<uint8_t>& out, std::string& why,
                     const std::atomic<bool>* cancel, std::string& interrupted_file) {
  try {
    out = read_whole_input_file(path, {max_gltf_file_bytes, cancel});
  } catch (const error& e) {
    why = e.reason();
    if (e.kind() == error_kind::interrupted) interrupted_file = path;
    return false;
  }
  return true;
}

// tinygltf also searches the current directory after the asset folder; joined with "." those
// paths are relative, so they never lie inside the (absolute) asset folder and are not found.
// A file outside the folder that exists is reported as existing so that read_whole_file can
// refuse it with a clear reason instead of tinygltf's "not found".
bool file_exists(const std::string& path, void* user) {
  if (const gltf_memory_asset* asset = static_cast<fs_context*>(user)->in_memory)
    return supplied_file(*asset, path) != nullptr;
  if (fs::path(path).is_relative()) return false;
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
  auto* context = static_cast<fs_context*>(user);
  if (context->in_memory) {
    *out = *supplied_file(*context->in_memory, path);  // file_exists found it
    return true;
  }
  // No bytes: tinygltf then leaves the image empty (a warning kiln ignores) and goes on.
  if (context->unused_image_files.count(canonical_key(path)) > 0) return true;
  if (!context->rules.allow_outside && !inside_asset_folder(path, context->rules)) {
    if (err) *err += "refers to a file outside the asset's folder (allow with --allow-outside-files)";
    return false;
  }
  std::string why;
  if (!read_file_bytes(path, *out, why, context->cancel, context->interrupted_file)) {
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
// OpenImageIO, later); the bytes of an image no material samples (a data URI) are dropped. For an
// image in a bufferView, tinygltf hands over a pointer it never bounds-checked against the
// buffer, so those bytes are not touched here.
bool keep_encoded_image(tinygltf::Image* image, const int index, std::string*, std::string*, int, int,
                        const unsigned char* bytes, int size, void* user) {
  image->as_is = true;
  if (image->bufferView >= 0) return true;
  const auto& used = static_cast<const fs_context*>(user)->image_used;
  if (index >= 0 && static_cast<size_t>(index) < used.size() && !used[static_cast<size_t>(index)])
    return true;
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
                      "glTF version " + quoted(version) + " is not supported (kiln reads glTF 2.x)");
}

// Why a known extension cannot be read, for the refusal; "" for the rest.
std::string why_unsupported(const std::string& name) {
  if (name == "KHR_texture_basisu")
    return ": no KTX2/Basis Universal decoder is available to kiln (Debian packages none); convert the "
           "textures to PNG, JPEG or WebP, or keep a PNG/JPEG source and leave the extension optional";
  return "";
}

void check_required_extensions(const std::vector<std::string>& required, const std::string& path) {
  const auto& supported = supported_extensions();
  for (size_t i = 0; i < required.size(); ++i) {
    const std::string& name = required[i];
    if (std::find(supported.begin(), supported.end(), name) == supported.end())
      throw input_error(path, pointer_join("/extensionsRequired", static_cast<int64_t>(i)),
                        "required extension " + shown(name) + " is not supported" + why_unsupported(name));
  }
}

// When tinygltf refuses a file, an unsupported required extension is usually the real cause
// (Draco primitives have accessors without bufferViews, which tinygltf rejects on its own), so
// look for one in the raw JSON and report it instead of tinygltf's symptom.
void check_required_extensions_in_json(const nlohmann::json& doc, const std::string& path) {
  if (!doc.is_object()) return;
  auto required = doc.find("extensionsRequired");
  if (required == doc.end() || !required->is_array()) return;
  std::vector<std::string> names;
  for (const auto& name : *required)
    names.push_back(name.is_string() ? name.get<std::string>() : name.dump());
  check_required_extensions(names, path);
}

void check_required_extensions_in_json(const uint8_t* text, size_t size, const std::string& path) {
  check_required_extensions_in_json(
      nlohmann::json::parse(text, text + size, nullptr, /*allow_exceptions=*/false), path);
}

// The deepest nesting of arrays and objects in JSON text, found without parsing: JSON parsers
// (and the destructors of what they build) recurse per level, so millions of '[' exhaust the
// stack. Stops counting once past `limit`.
size_t json_nesting_depth(const uint8_t* text, size_t size, size_t limit) {
  size_t depth = 0, deepest = 0;
  bool in_string = false;
  for (size_t i = 0; i < size && deepest <= limit; ++i) {
    const uint8_t c = text[i];
    if (in_string) {
      if (c == '\\')
        ++i;  // skip the escaped character
      else if (c == '"')
        in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      deepest = std::max(deepest, ++depth);
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;
    }
  }
  return deepest;
}

// Checks the JSON before tinygltf parses it: size and nesting within the limits, the node count
// within its limit, and every buffer and image URI inside the asset's folder. glTF URIs are
// relative references: an absolute path or a file: URI is never followed; ".." that leaves the
// folder only with the allow option. Each refusal names the JSON pointer. Records in context
// which images materials sample. Returns the JSON text tinygltf should parse instead when
// compressed geometry needed placeholders (gltf_compressed_json.h), or "" when the text is fine.
std::string check_json_before_parsing(const uint8_t* text, size_t size, const std::string& path,
                                      fs_context& context, const gltf_limits& limits,
                                      const buffer_sources& sources) {
  if (size > limits.max_json_bytes)
    throw input_error(path, "",
                      "JSON is " + std::to_string(size) + " bytes, over the limit of " +
                          std::to_string(limits.max_json_bytes) + " (--max-json-bytes)");
  if (json_nesting_depth(text, size, limits.max_json_depth) > limits.max_json_depth)
    throw input_error(
        path, "",
        "JSON nests deeper than " + std::to_string(limits.max_json_depth) + " levels (--max-json-depth)");
  if (context.memory) context.memory->add(json_parse_bytes(text, size), path, "the JSON text and its parse");
  nlohmann::json doc = nlohmann::json::parse(text, text + size, nullptr, /*allow_exceptions=*/false);
  if (doc.is_discarded()) check_json_syntax(text, size, path);
  if (!doc.is_object())
    throw input_error(
        path, "",
        std::string("invalid glTF: the top-level JSON value is ") + doc.type_name() + ", not an object");
  auto nodes = doc.find("nodes");
  if (nodes != doc.end() && nodes->is_array() && nodes->size() > limits.max_nodes)
    throw input_error(path, "/nodes",
                      std::to_string(nodes->size()) + " nodes, over the limit of " +
                          std::to_string(limits.max_nodes) + " (--max-nodes)");
  for_each_file_uri(doc, [&](const std::string& where, const std::string& uri) {
    if (!context.in_memory)
      checked_uri_files(path, where, uri, context.rules);
    else if (!supplied_file(*context.in_memory, uri))
      throw input_error(
          path, where,
          "names " + quoted(uri) +
              ", which was not given with the asset in memory (nothing is read from files for it)");
  });
  // An unsupported required extension explains what follows from it (Draco's accessors have no
  // bufferViews), so it is reported first.
  check_required_extensions_in_json(doc, path);
  const bool placeholders = add_compression_placeholders(doc, path);
  check_what_tinygltf_refuses(doc, path, sources);
  check_integer_properties(doc, path);
  check_camera_numbers(doc, path);
  if (context.memory) context.memory->add(declared_buffer_bytes(doc), path, "the buffers");
  context.image_used = images_used_by_materials(doc);
  if (context.in_memory) return placeholders ? doc.dump() : std::string();  // every file is here
  context.unused_image_files = unused_image_files(doc, context.image_used, context.rules.folder_prefix);
  refuse_missing_image_files(doc, context.rules.folder_prefix, path);
  return placeholders ? doc.dump() : std::string();
}

}  // namespace

const std::vector<std::string>& supported_extensions() {
  static const std::vector<std::string> names = {"KHR_lights_punctual",
                                                 "KHR_materials_emissive_strength",
                                                 "KHR_materials_ior",
                                                 "KHR_materials_specular",
                                                 "KHR_materials_clearcoat",
                                                 "KHR_materials_sheen",
                                                 "KHR_materials_iridescence",
                                                 "KHR_materials_anisotropy",
                                                 "KHR_materials_dispersion",
                                                 "KHR_materials_diffuse_transmission",
                                                 "KHR_materials_transmission",
                                                 "KHR_materials_volume",
                                                 "KHR_texture_transform",
                                                 "KHR_materials_unlit",
                                                 "KHR_materials_variants",
                                                 "KHR_mesh_quantization",
                                                 "KHR_draco_mesh_compression",
                                                 "EXT_meshopt_compression",
                                                 "EXT_texture_webp",
                                                 "EXT_mesh_gpu_instancing",
                                                 "KILN_quadric"};
  return names;
}

tinygltf::Model parse_gltf_file(const std::string& path, const gltf_load_options& options,
                                memory_charge* held) {
  // The file's size from stat(), before it is read; a file over the size limit is refused by the
  // reader, in its own words.
  const gltf_memory_asset* in_memory = options.in_memory.get();
  std::vector<uint8_t> read;
  fs::path folder;  // tinygltf looks for an in-memory asset's files under their URIs alone
  fs_context context;
  context.in_memory = in_memory;
  context.cancel = options.cancel;
  context.memory = held;
  if (!in_memory) {
    std::error_code size_error;
    if (held && input_file_problem(path, max_gltf_file_bytes).empty())
      if (const uintmax_t size = fs::file_size(path, size_error); !size_error)
        held->add(size, path, "the glTF file");
    // Throws for a FIFO, a device or a folder given as the asset, before a byte is read.
    read = read_whole_input_file(path, {max_gltf_file_bytes, options.cancel});
    std::error_code ec;
    folder = fs::absolute(fs::path(path), ec).parent_path();
    if (ec) throw input_error(path, "", "cannot resolve the asset's folder: " + ec.message());
    context.rules = asset_uri_rules(path, options.allow_files_outside_folder);
  } else if (in_memory->document.size() > max_gltf_file_bytes) {
    throw input_error(path, "", "the asset is over kiln's size limit of " + memory_text(max_gltf_file_bytes));
  } else if (held) {
    held->add(in_memory->document.size(), path, "the glTF file");
  }
  const std::vector<uint8_t>& bytes = in_memory ? in_memory->document : read;

  tinygltf::TinyGLTF parser;
  const bool is_glb = ends_with_glb(path) || has_glb_magic(bytes);
  parser.SetFsCallbacks(
      tinygltf::FsCallbacks{&file_exists, &expand_file_path, &read_whole_file, &write_whole_file, &context});
  parser.SetImageLoader(&keep_encoded_image, &context);

  tinygltf::Model model;
  std::string err;
  std::string warn;
  bool ok = false;
  size_t json_offset = 0;
  size_t json_length = bytes.size();
  try {
    if (is_glb) {
      const glb_layout layout = check_glb_container(bytes, path);
      json_offset = layout.json_offset;
      json_length = layout.json_length;
      buffer_sources sources{context.rules.folder_prefix, true, layout.has_bin, layout.bin_length,
                             in_memory ? &in_memory->files : nullptr};
      const std::string replaced = check_json_before_parsing(bytes.data() + json_offset, json_length, path,
                                                             context, options.limits, sources);
      if (has_utf8_bom(bytes.data() + layout.json_offset, layout.json_length))
        throw input_error(path, "", "GLB JSON chunk starts with a byte order mark, which glTF forbids");
      const std::vector<uint8_t> rebuilt =
          replaced.empty() ? std::vector<uint8_t>() : glb_with_json(bytes, layout, replaced);
      const std::vector<uint8_t>& glb = replaced.empty() ? bytes : rebuilt;
      ok = parser.LoadBinaryFromMemory(&model, &err, &warn, glb.data(), static_cast<unsigned int>(glb.size()),
                                       folder.string());
    } else {
      if (has_utf8_bom(bytes.data(), bytes.size()))
        throw input_error(path, "", "JSON starts with a byte order mark, which glTF forbids");
      const std::string replaced =
          check_json_before_parsing(bytes.data(), bytes.size(), path, context, options.limits,
                                    buffer_sources{context.rules.folder_prefix, false, false, 0,
                                                   in_memory ? &in_memory->files : nullptr});
      const char* text = replaced.empty() ? reinterpret_cast<const char*>(bytes.data()) : replaced.data();
      const size_t text_size = replaced.empty() ? bytes.size() : replaced.size();
      ok = parser.LoadASCIIFromString(&model, &err, &warn, text, static_cast<unsigned int>(text_size),
                                      folder.string());
    }
  } catch (const kiln::error&) {
    throw;
  } catch (const std::bad_alloc&) {
    throw;  // not the file's fault: the job reports it with the stage it reached
  } catch (const std::exception& e) {
    throw input_error(path, "", std::string("invalid glTF: ") + e.what());
  }
  if (!context.interrupted_file.empty())
    throw error(error_kind::interrupted, context.interrupted_file, "",
                "interrupted while reading, nothing written");
  if (!ok) {
    check_required_extensions_in_json(bytes.data() + json_offset, json_length, path);
    std::string line = first_line(err);
    if (line.empty()) line = "tinygltf could not parse the file";
    throw input_error(path, "", "invalid glTF: " + shown(line));
  }
  check_version(model, path);
  check_required_extensions(model.extensionsRequired, path);
  return model;
}

}  // namespace kiln::gltf_internal
