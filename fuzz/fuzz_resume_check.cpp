// libFuzzer target: the resume check's readers (io/exr/exr_verify.h, io/exr/preview_record.h) on
// damaged outputs. The input's first byte picks what the rest is: 0 a flat EXR, 1 a deep EXR, 2 a
// PNG preview, 3 a JPEG preview (mod 4). A check must end in a verdict, never a crash, a sanitizer
// report or an escaped exception, within its memory budget; and a flat file it passes must read
// back through read_exr.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "core/error.h"
#include "core/memory_budget.h"
#include "io/exr/exr_reader.h"
#include "io/exr/exr_verify.h"
#include "io/exr/preview_record.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return -1;
  static const char* const extensions[4] = {".exr", ".deep.exr", ".png", ".jpg"};
  const int kind = data[0] % 4;
  const std::string path = "/tmp/fuzz_resume_check_" + std::to_string(::getpid()) + extensions[kind];
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) std::abort();
  std::fwrite(data + 1, 1, size - 1, f);
  std::fclose(f);
  kiln::memory_budget budget(uint64_t(256) << 20);
  if (kind == 0) {
    if (kiln::check_flat_exr(path, {}, &budget).problem.empty()) {
      try {
        kiln::memory_budget read_budget(uint64_t(256) << 20);
        kiln::read_exr(path, &read_budget);
      } catch (const kiln::error& e) {
        std::fprintf(stderr, "fuzz_resume_check: passed the check, then: %s\n", e.what());
        std::abort();
      }
    }
  } else if (kind == 1) {
    kiln::check_deep_exr(path, {}, &budget);
  } else {
    kiln::preview_file_problem(path, 8, 6);
  }
  if (budget.used() != 0) {
    std::fprintf(stderr, "fuzz_resume_check: %llu bytes of the budget not given back\n",
                 static_cast<unsigned long long>(budget.used()));
    std::abort();
  }
  ::unlink(path.c_str());
  return 0;
}
