// The scene meshes of glTF primitives, built once per distinct geometry and shared by the
// instances that place them, or posed once per distinct pose when a skin or morph weights deform
// them.
// Internal to io/gltf.
#pragma once

#include <tiny_gltf.h>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "io/gltf/gltf_build_context.h"

namespace kiln::gltf_internal {

// Reads a float accessor; NaN or infinity (they would poison bounds and traversal) is an error
// naming `name` at `where`.
std::vector<float> read_finite(build_context& ctx, int accessor, const std::string& where,
                               const std::string& name);

// The primitive's vertex indices in its own topology (sequential when it has no indices); an
// index at or beyond vertex_count is an error at `where`/indices.
std::vector<uint32_t> primitive_indices(build_context& ctx, const tinygltf::Primitive& prim,
                                        size_t vertex_count, const std::string& where);

// Builds the kiln mesh of one glTF primitive, or -1 when it has nothing to render. With a
// deformation the mesh is the primitive posed by that node.
int32_t build_mesh(build_context& ctx, int mesh_index, int prim_index, const deformation* posed = nullptr);

// A frame of a sequence: mesh `previous` of the last frame's scene (ctx.reuse), which no
// animation changes, moved into this frame's scene; its index there (-1 stays -1).
int32_t take_over_mesh(build_context& ctx, int32_t previous);

// The shared scene mesh of a rigid primitive (built on first use, -1: nothing to render):
// primitives built from the same accessors into the same attributes share one.
int32_t mesh_for(build_context& ctx, int mesh_index, int prim_index);

}  // namespace kiln::gltf_internal
