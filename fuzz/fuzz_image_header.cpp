// libFuzzer target: arbitrary bytes as an encoded image through the header reader that runs before
// any decoder (io/gltf/image_header.h). It must never read outside the bytes (ASan), and a size it
// reports must come with a format: the texel limit is checked against these numbers alone.
#include <cstdint>
#include <cstdio>
#include <cstdlib>

#include "io/gltf/image_header.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const kiln::gltf_internal::image_header h = kiln::gltf_internal::read_image_header(data, size);
  if ((h.width != 0 || h.height != 0) && h.format.empty()) {
    std::fprintf(stderr, "fuzz_image_header: a size without a format\n");
    std::abort();
  }
  return 0;
}
