#include "io/gltf/gltf_precheck.h"

#include <filesystem>
#include <system_error>
#include <vector>

#include "core/error.h"
#include "core/message_text.h"
#include "io/gltf/gltf_common.h"

namespace kiln::gltf_internal {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

// Follows the parser through the document so that an error names where it happened: one frame
// per open object or array, holding the current key or the index of the next element.
class pointer_tracker : public nlohmann::json_sax<json> {
 public:
  std::string location;  // pointer reported with the error
  std::string reason;

  bool null() override { return value_done(); }
  bool boolean(bool) override { return value_done(); }
  bool number_integer(number_integer_t) override { return value_done(); }
  bool number_unsigned(number_unsigned_t) override { return value_done(); }
  bool number_float(number_float_t, const string_t&) override { return value_done(); }
  bool string(string_t&) override { return value_done(); }
  bool binary(binary_t&) override { return value_done(); }
  bool start_object(std::size_t) override { return open(false); }
  bool key(string_t& name) override {
    stack_.back().key = name;
    return true;
  }
  bool end_object() override { return close(); }
  bool start_array(std::size_t) override { return open(true); }
  bool end_array() override { return close(); }

  bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception& e) override {
    std::string what = e.what();
    const size_t bracket = what.find("] ");
    if (what.rfind("[json.exception.", 0) == 0 && bracket != std::string::npos)
      what = what.substr(bracket + 2);
    // A number out of range is a complete value, so the pointer names it; any other error sits
    // between tokens, so only the enclosing object or array is certain.
    const bool number_overflow = e.id == 406;
    location = path(number_overflow ? stack_.size() : stack_.empty() ? 0 : stack_.size() - 1);
    reason = number_overflow ? what + ": glTF numbers must be finite" : "invalid glTF: not JSON: " + what;
    return false;
  }

 private:
  struct frame {
    bool array = false;
    size_t next = 0;
    std::string key;
  };

  std::string path(size_t depth) const {
    std::string out;
    for (size_t i = 0; i < depth; ++i)
      out = stack_[i].array ? pointer_join(out, int64_t(stack_[i].next)) : pointer_join(out, stack_[i].key);
    return out;
  }
  bool value_done() {
    if (!stack_.empty() && stack_.back().array) ++stack_.back().next;
    return true;
  }
  bool open(bool array) {
    stack_.push_back(frame{array, 0, {}});
    return true;
  }
  bool close() {
    stack_.pop_back();
    return value_done();
  }

  std::vector<frame> stack_;
};

// The decoded size of a base64 payload: only the alphabet, then at most two '=' that pad to a
// multiple of 4 characters. Unpadded payloads are accepted, as tinygltf decodes them too.
bool decoded_base64_size(const std::string& text, size_t& size) {
  size_t n = text.size();
  size_t padding = 0;
  while (n > 0 && text[n - 1] == '=' && padding < 2) --n, ++padding;
  if (n == 0 || n % 4 == 1 || (padding > 0 && text.size() % 4 != 0)) return false;
  for (size_t i = 0; i < n; ++i) {
    const char c = text[i];
    if (!((c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '+' || c == '/'))
      return false;
  }
  size = n / 4 * 3 + (n % 4 == 2 ? 1 : n % 4 == 3 ? 2 : 0);
  return true;
}

// The data-URI headers tinygltf recognises; it decodes any of them for buffers and images alike.
const std::vector<std::string>& data_uri_headers() {
  static const std::vector<std::string> headers = {"data:application/octet-stream;base64,",
                                                   "data:application/gltf-buffer;base64,",
                                                   "data:image/png;base64,",
                                                   "data:image/jpeg;base64,",
                                                   "data:image/bmp;base64,",
                                                   "data:image/gif;base64,",
                                                   "data:text/plain;base64,"};
  return headers;
}

// Checks a data URI's header and payload; returns the decoded size.
size_t check_data_uri(const std::string& uri, bool image, const std::string& path, const std::string& where) {
  for (const std::string& header : data_uri_headers()) {
    if (uri.rfind(header, 0) != 0) continue;
    size_t size = 0;
    if (!decoded_base64_size(uri.substr(header.size()), size))
      throw input_error(path, where, "the data URI's base64 payload is malformed or empty");
    return size;
  }
  const std::string& expected = data_uri_headers()[image ? 2 : 0];
  throw input_error(
      path, where,
      "malformed data URI " + quoted(uri.substr(0, 48)) + " (expected it to start with " + expected + ")");
}

const json* find_array(const json& doc, const char* name) {
  auto it = doc.find(name);
  return it != doc.end() && it->is_array() ? &*it : nullptr;
}

bool is_index(const json& value) { return value.is_number_integer() && value.get<int64_t>() >= 0; }

void check_buffer(const json& buffer, size_t i, const std::string& path, const buffer_sources& sources) {
  const std::string where = pointer("buffers", int64_t(i));
  if (!buffer.is_object()) return;
  auto length_it = buffer.find("byteLength");
  if (length_it == buffer.end() || !length_it->is_number_unsigned() || length_it->get<uint64_t>() == 0)
    throw input_error(path, pointer_join(where, "byteLength"), "byteLength must be an integer of at least 1");
  const uint64_t length = length_it->get<uint64_t>();
  auto uri_it = buffer.find("uri");
  if (uri_it == buffer.end() || !uri_it->is_string() || uri_it->get<std::string>().empty()) {
    if (!sources.is_glb)
      throw input_error(path, where, "buffer has no 'uri' (only a .glb's buffer may use the BIN chunk)");
    if (!sources.has_bin) throw input_error(path, where, "buffer has no 'uri' and the GLB has no BIN chunk");
    if (length > sources.bin_length)
      throw input_error(path, pointer_join(where, "byteLength"),
                        "byteLength " + std::to_string(length) + " exceeds the BIN chunk's " +
                            std::to_string(sources.bin_length) + " bytes");
    return;
  }
  const std::string uri = uri_it->get<std::string>();
  const std::string uri_where = pointer_join(where, "uri");
  if (uri.rfind("data:", 0) == 0) {
    const size_t size = check_data_uri(uri, false, path, uri_where);
    if (size != length)
      throw input_error(path, pointer_join(where, "byteLength"),
                        "byteLength is " + std::to_string(length) + " but the data URI holds " +
                            std::to_string(size) + " bytes");
    return;
  }
  // tinygltf requires the file's size to equal byteLength exactly.
  if (sources.memory_files) {
    const auto supplied = sources.memory_files->find(uri);  // present: the URI check saw to it
    if (supplied != sources.memory_files->end() && supplied->second.size() != length)
      throw input_error(path, pointer_join(where, "byteLength"),
                        "byteLength is " + std::to_string(length) + " but the bytes given for " +
                            quoted(uri) + " are " + std::to_string(supplied->second.size()));
    return;
  }
  std::error_code ec;
  const fs::path file = fs::path(sources.folder_prefix) / percent_decoded(uri);
  if (!fs::is_regular_file(file, ec))
    throw input_error(path, uri_where, "buffer file " + quoted(uri) + " not found");
  const uintmax_t size = fs::file_size(file, ec);
  if (!ec && size != length)
    throw input_error(path, pointer_join(where, "byteLength"),
                      "byteLength is " + std::to_string(length) + " but " + quoted(uri) + " has " +
                          std::to_string(size) + " bytes");
}

void check_buffer_views(const json& doc, const std::string& path) {
  const json* views = find_array(doc, "bufferViews");
  if (!views) return;
  for (size_t i = 0; i < views->size(); ++i) {
    const json& view = (*views)[i];
    if (!view.is_object() || !view.contains("byteStride")) continue;
    const json& stride = view["byteStride"];
    if (!stride.is_number_unsigned() || stride.get<uint64_t>() < 4 || stride.get<uint64_t>() > 252 ||
        stride.get<uint64_t>() % 4 != 0)
      throw input_error(path, pointer_join(pointer("bufferViews", int64_t(i)), "byteStride"),
                        "byteStride must be a multiple of 4 from 4 to 252, got " + stride.dump());
  }
}

void check_images(const json& doc, const std::string& path) {
  const json* images = find_array(doc, "images");
  if (!images) return;
  const json* views = find_array(doc, "bufferViews");
  const size_t view_count = views ? views->size() : 0;
  for (size_t i = 0; i < images->size(); ++i) {
    const json& image = (*images)[i];
    if (!image.is_object()) continue;
    const std::string where = pointer("images", int64_t(i));
    auto uri = image.find("uri");
    if (uri != image.end() && uri->is_string() && uri->get<std::string>().rfind("data:", 0) == 0)
      check_data_uri(uri->get<std::string>(), true, path, pointer_join(where, "uri"));
    auto view = image.find("bufferView");
    if (view != image.end() && (!is_index(*view) || view->get<uint64_t>() >= view_count))
      throw input_error(path, pointer_join(where, "bufferView"),
                        "/bufferViews/" + shown(view->dump()) + " does not exist (file has " +
                            std::to_string(view_count) + " bufferViews)");
  }
}

// tinygltf reads every index accessor's bufferView while parsing: both must exist.
void check_index_accessors(const json& doc, const std::string& path) {
  const json* meshes = find_array(doc, "meshes");
  if (!meshes) return;
  const json* accessors = find_array(doc, "accessors");
  const json* views = find_array(doc, "bufferViews");
  const size_t accessor_count = accessors ? accessors->size() : 0, view_count = views ? views->size() : 0;
  for (size_t m = 0; m < meshes->size(); ++m) {
    const json& mesh = (*meshes)[m];
    if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array()) continue;
    const json& primitives = mesh["primitives"];
    for (size_t p = 0; p < primitives.size(); ++p) {
      if (!primitives[p].is_object() || !primitives[p].contains("indices")) continue;
      const json& indices = primitives[p]["indices"];
      const std::string where = pointer_join(
          pointer_join(pointer_join(pointer("meshes", int64_t(m)), "primitives"), int64_t(p)), "indices");
      if (!is_index(indices) || indices.get<uint64_t>() >= accessor_count)
        throw input_error(path, where,
                          "/accessors/" + shown(indices.dump()) + " does not exist (file has " +
                              std::to_string(accessor_count) + " accessors)");
      const json& accessor = (*accessors)[indices.get<size_t>()];
      const json* view =
          accessor.is_object() && accessor.contains("bufferView") ? &accessor["bufferView"] : nullptr;
      if (!view || !is_index(*view) || view->get<uint64_t>() >= view_count)
        throw input_error(path, where,
                          "index accessor " + shown(indices.dump()) +
                              " has no valid bufferView (indices need stored data)");
    }
  }
}

void check_spot_lights(const json& doc, const std::string& path) {
  auto extensions = doc.find("extensions");
  if (extensions == doc.end() || !extensions->is_object()) return;
  auto punctual = extensions->find("KHR_lights_punctual");
  if (punctual == extensions->end() || !punctual->is_object()) return;
  const json* lights = find_array(*punctual, "lights");
  if (!lights) return;
  for (size_t i = 0; i < lights->size(); ++i) {
    const json& light = (*lights)[i];
    if (light.is_object() && light.value("type", json()) == "spot" &&
        (!light.contains("spot") || !light["spot"].is_object()))
      throw input_error(path, pointer_join("/extensions/KHR_lights_punctual/lights", int64_t(i)),
                        "a spot light needs a 'spot' object with its cone angles");
  }
}

}  // namespace

void check_json_syntax(const uint8_t* text, size_t size, const std::string& path) {
  pointer_tracker tracker;
  if (json::sax_parse(text, text + size, &tracker)) return;
  throw input_error(path, tracker.location, tracker.reason);
}

void check_what_tinygltf_refuses(const json& doc, const std::string& path, const buffer_sources& sources) {
  if (const json* buffers = find_array(doc, "buffers"))
    for (size_t i = 0; i < buffers->size(); ++i) check_buffer((*buffers)[i], i, path, sources);
  check_buffer_views(doc, path);
  check_images(doc, path);
  check_index_accessors(doc, path);
  check_spot_lights(doc, path);
}

}  // namespace kiln::gltf_internal
