// Loads a glTF 2.0 asset (.gltf with external or data-URI buffers, or .glb) into a Scene.
// The only module that knows glTF. Every reference and accessor is validated against its
// buffer before any byte is read; bad input throws kiln::error with the file, the JSON pointer
// (e.g. /accessors/7) and the reason.
#pragma once

#include <atomic>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/error.h"  // callers catch the kiln::error this throws
#include "core/memory_budget.h"
#include "scene/scene.h"

namespace kiln {

struct gltf_summary;  // io/gltf/gltf_summary.h

// Bounds on what a file may make the loader do, so a hostile or broken file is refused with a
// message instead of exhausting memory, time or the stack. Defaults cover every real asset kiln
// has met with a wide margin; the CLI can raise them.
struct gltf_limits {
  size_t max_json_bytes = size_t(512) << 20;  // the JSON text (GLB: its JSON chunk)
  size_t max_json_depth = 512;                // nesting of arrays and objects; glTF itself needs < 10
  size_t max_nodes = 1000000;                 // entries in "nodes"
  size_t max_instances = 1000000;             // scene instances once EXT_mesh_gpu_instancing adds its own
  uint64_t max_texels = uint64_t(1) << 28;    // width × height of one image, checked before decoding
};

// Files larger than this are refused, the asset and every file it names: tinygltf passes sizes
// through int and unsigned int.
constexpr uint64_t max_gltf_file_bytes = uint64_t(2147483647);

// An asset held in memory (kiln.load of a dict or bytes): the .gltf JSON or the .glb, and the files
// its buffer and image URIs name, by the URI as the JSON writes it. The loader reads nothing from the
// file system for it: a URI that is not here is refused, naming its JSON pointer.
struct gltf_memory_asset {
  std::vector<uint8_t> document;
  std::map<std::string, std::vector<uint8_t>> files;
};

struct gltf_load_options {
  // When set, the asset itself (the path then only names it in messages).
  std::shared_ptr<const gltf_memory_asset> in_memory;
  int scene_index = -1;  // -1: the file's default scene (or scene 0 when none is marked)
  // Buffer and image URIs may name files outside the asset's folder (absolute paths, ".."
  // escapes). Off by default: a scene file must not read arbitrary files on a farm node.
  bool allow_files_outside_folder = false;
  gltf_limits limits;
  // When set and raised (SIGINT/SIGTERM), reading files stops and loading throws kiln::error of
  // kind interrupted.
  const std::atomic<bool>* cancel = nullptr;
  int threads = 0;  // threads that decode images (0: all cores); the scene is the same for any count
  // When set, the JSON and its parse, buffers, meshes and decoded images are charged to it before
  // they are allocated; what would pass its limit is refused (kiln::error, input). The scene's
  // meshes and images stay charged; what loading alone needs is released when it returns.
  memory_budget* memory = nullptr;
  // The pose (glTF 2.0 §3.11): the chosen animations sampled at `time` seconds (finite; before the
  // first key or after the last the end values hold). `animation`: "" or "all" plays every
  // animation of the file together, else one animation by name or index. A file without
  // animations ignores the time; "none" is the rest pose; morph weights and skins pose the meshes either way.
  double time = 0.0;
  std::string animation;
  // KHR_materials_variants: the variant whose materials the mapped primitives take (its name or
  // index); "": every primitive keeps its own material.
  std::string variant;
};

// Throws kiln::error (kind input) on any invalid or unsupported input.
scene load_gltf(const std::string& path, const gltf_load_options& options = {});

// The KHR_materials_variants variants of the file, in order (empty when it has none). Reads and
// parses the file as load_gltf does; throws kiln::error (input) when that fails.
std::vector<std::string> gltf_material_variants(const std::string& path,
                                                const gltf_load_options& options = {});

// One asset posed at many times (the frames of a shot): the file is read, parsed and validated
// once, and each frame builds only what can change with time. load_gltf is one pose of one.
class gltf_sequence {
 public:
  // Reads and validates the file (options.time is unused; pose takes the time). Throws kiln::error.
  gltf_sequence(const std::string& path, const gltf_load_options& options);
  ~gltf_sequence();
  gltf_sequence(const gltf_sequence&) = delete;
  gltf_sequence& operator=(const gltf_sequence&) = delete;

  // The scene posed at `time` seconds, equal to load_gltf at that time. `previous`, the scene the
  // last call returned, gives up what no animation changes, moved instead of built again: every
  // rigid mesh, every skinned or morphed one whose joints and weights no channel drives, and the
  // materials, textures and decoded images (the loader's own; images a client appended stay
  // behind). Drop `previous` afterwards. Mesh indices and instance order are the same in every
  // frame unless a transform turns singular at some time. `posed_meshes` receives the meshes
  // posed anew for this time (those an animation deforms): a backend refits those and moves every
  // instance. stats.warnings holds those new to the sequence, after the ones `previous` still held
  // (moved from it): a client clears a scene's warnings once it has given them. Throws kiln::error
  // (input) for bad input at this time.
  scene pose(double time, scene* previous = nullptr, std::vector<uint32_t>* posed_meshes = nullptr);

  // Whether animations drive the file's nodes, so frames differ.
  bool animated() const;
  // The first and last keyframe times of the chosen animations, in seconds ({0, 0} when not
  // animated).
  std::pair<double, double> time_range() const;
  // What the file declares (io/gltf/gltf_summary.h), from the parse it keeps.
  gltf_summary summary() const;

 private:
  struct state;
  std::unique_ptr<state> state_;
};

}  // namespace kiln
