// libFuzzer target: arbitrary bytes as a KHR_draco_mesh_compression stream through kiln's decoder
// wrapper (io/gltf/draco_stream.h). The first byte b asks for attribute ids 0 to (b / 24) % 4, each of
// 1 + (b / 6) % 4 components in glTF component type number b % 6 (FLOAT, BYTE, UNSIGNED_BYTE, SHORT,
// UNSIGNED_SHORT, UNSIGNED_INT); the rest is the stream. A corrupt stream must come back as a problem, never
// a crash (ASan); a stream that decodes must give indices below its point count and attributes of exactly the
// size asked for. libdraco itself comes from Debian's archive without instrumentation: coverage feedback
// reaches kiln's wrapper only, while ASan still checks every access kiln makes to the decoded data.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "io/gltf/draco_stream.h"

namespace {

void fail(const char* what) {
  std::fprintf(stderr, "fuzz_draco_stream: %s\n", what);
  std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  static const int types[] = {5126, 5120, 5121, 5122, 5123, 5125};
  static const size_t sizes[] = {4, 1, 1, 2, 2, 4};
  const size_t pick = data[0] % 6, components = 1 + (data[0] / 6) % 4;
  std::vector<kiln::gltf_internal::draco_attribute_want> wants;
  for (uint32_t id = 0; id <= uint32_t(data[0] / 24) % 4; ++id)
    wants.push_back({id, types[pick], components});
  std::string problem;
  // A glTF file's accessors bound what a stream may declare; here a million of each stands in.
  const kiln::gltf_internal::draco_stream_limits limits{1u << 20, 1u << 20};
  const auto g = kiln::gltf_internal::decode_draco_stream(data + 1, size - 1, wants, limits, problem);
  if (!g) {
    if (problem.empty()) fail("a refusal without a reason");
    return 0;
  }
  for (uint32_t index : g->indices)
    if (index >= g->point_count) fail("an index past the points");
  if (g->indices.size() % 3 != 0) fail("indices that are not triangles");
  if (g->attributes.size() != wants.size()) fail("a missing attribute");
  for (size_t i = 0; i < wants.size(); ++i)
    if (g->attributes[i].size() != size_t(g->point_count) * wants[i].components * sizes[pick])
      fail("an attribute of the wrong size");
  return 0;
}
