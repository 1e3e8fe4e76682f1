// libFuzzer target: arbitrary bytes through kiln's own PNG and JPEG decoding
// (io/image_codecs/direct_decode.h), which reads glTF images before any module is opened. libpng and
// libjpeg leave by longjmp on an error: nothing may leak (LeakSanitizer), nothing may be read past
// the bytes (ASan), and a decoded image must hold exactly the texels its size says.
#include <cstdint>
#include <cstdio>
#include <cstdlib>

#include "io/image_codecs/direct_decode.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::optional<kiln::image> out = kiln::decode_directly(data, size, uint64_t(1) << 22);
  if (out &&
      (out->width <= 0 || out->height <= 0 ||
       out->texels8.size() != size_t(out->width) * size_t(out->height) * 4 || !out->texels32.empty())) {
    std::fprintf(stderr, "fuzz_image_decode: an image whose texels do not match its size\n");
    std::abort();
  }
  return 0;
}
