#include "job/render_fingerprint.h"

#include <cstdio>
#include <filesystem>
#include <system_error>

#include "io/colour/colour_loader.h"
#include "io/exr/environment_reader.h"
#include "io/file/input_file.h"
#include "io/gltf/gltf_references.h"
#include "job/memory_limit.h"
#include "job/option_table.h"

namespace kiln {

namespace {

namespace fs = std::filesystem;

// FNV-1a, 64 bit: cheap and stable across platforms; a fingerprint, not a defence.
struct fnv1a {
  uint64_t h = 0xcbf29ce484222325ull;
  void add(const char* data, size_t size) {
    for (size_t k = 0; k < size; ++k) h = (h ^ uint8_t(data[k])) * 0x100000001b3ull;
  }
  void add(const std::string& text) { add(text.data(), text.size() + 1); }  // the NUL separates fields
  std::string hex() const {
    char text[17];
    std::snprintf(text, sizeof text, "%016llx", (unsigned long long)h);
    return text;
  }
};

// Hashes the file's bytes through the input-file reader: a FIFO or a device is refused before a
// byte is read (input error, exit 2), and SIGINT/SIGTERM stop the hash within a chunk. A missing
// file hashes as nothing; the loader names it in its own words.
void add_file(fnv1a& hash, const std::string& path, uint64_t max_bytes, const std::atomic<bool>* cancel,
              const std::string& where = "") {
  if (input_file_missing(path)) return;
  read_input_file(path, {max_bytes, cancel, "", where},
                  [&hash](const char* bytes, size_t count) { hash.add(bytes, count); });
}

}  // namespace

render_fingerprint make_fingerprint(const render_options& options, const std::atomic<bool>* cancel) {
  fnv1a inputs, scene;      // the asset's bytes go into both: read once
  if (options.in_memory) {  // the document, and each file it was given with by its URI and bytes
    const std::vector<uint8_t>& document = options.in_memory->document;
    inputs.add(reinterpret_cast<const char*>(document.data()), document.size());
    scene.add(reinterpret_cast<const char*>(document.data()), document.size());
    for (const auto& [uri, bytes] : options.in_memory->files) {
      inputs.add(uri);
      fnv1a file;
      file.add(reinterpret_cast<const char*>(bytes.data()), bytes.size());
      inputs.add(file.hex());
    }
  } else if (!input_file_missing(options.input))
    read_input_file(options.input, {max_gltf_file_bytes, cancel, "", ""},
                    [&](const char* bytes, size_t count) {
                      inputs.add(bytes, count);
                      scene.add(bytes, count);
                    });
  // Each referenced file by its name and bytes, so renaming a buffer counts as a change too. The
  // list comes through the loader's URI rule: nothing outside the folder, no FIFO, no device.
  // A missing asset names nothing; the loader reports it.
  if (!options.in_memory && !input_file_missing(options.input)) {
    gltf_load_options rules;
    rules.allow_files_outside_folder = options.allow_outside_files;
    rules.limits.max_json_bytes = options.limits.max_json_bytes;
    rules.cancel = cancel;
    // Finding the references parses the JSON: not when that parse would pass the job's memory
    // budget (the loader then refuses the file).
    memory_budget budget(options.max_memory ? options.max_memory : default_memory_budget());
    rules.memory = &budget;
    std::error_code ec;
    const fs::path folder = fs::weakly_canonical(fs::absolute(options.input, ec).parent_path(), ec);
    for (const std::string& file : gltf_referenced_files(options.input, rules)) {
      inputs.add(fs::path(file).lexically_relative(folder).string());
      fnv1a bytes;
      add_file(bytes, file, max_gltf_file_bytes, cancel);
      inputs.add(bytes.hex());
    }
  }
  if (!options.environment.empty()) {
    inputs.add("environment");
    fnv1a bytes;
    add_file(bytes, options.environment, max_environment_file_bytes, cancel, "--environment");
    inputs.add(bytes.hex());
  }
  if (!options.working_space.empty()) {
    // The config decides the working space's matrix, whichever names it (--ocio-config, $OCIO, kiln's own).
    const colour_config_source config = find_colour_config(options.ocio_config);
    inputs.add("ocio_config");
    fnv1a bytes;
    add_file(bytes, config.path, max_colour_config_bytes, cancel, config.named_by);
    inputs.add(bytes.hex());
  }
  render_fingerprint hashed;
  hashed.input_hash = inputs.hex();
  hashed.scene_hash = scene.hex();
  return fingerprint_with_settings(hashed, options);
}

render_fingerprint fingerprint_with_settings(const render_fingerprint& inputs,
                                             const render_options& options) {
  fnv1a settings, frame;
  for (const std::string& argument : canonical_render_arguments(options, region_arguments::include))
    settings.add(argument);
  for (const std::string& argument : canonical_render_arguments(options, region_arguments::omit))
    frame.add(argument);
  return {inputs.input_hash, settings.hex(), frame.hex(), inputs.scene_hash};
}

}  // namespace kiln
