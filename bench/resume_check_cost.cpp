// build/bench/resume_check_cost: what `kiln batch --resume` spends checking one output (io/exr/
// exr_verify.h), against reading it whole as the check before content checksums did (read_exr),
// and what the writer adds under a lossless codec (one CRC-32 pass over the pixels). A plain
// program: speed is measured here, never asserted.
//   resume_check_cost FILE.exr [ROUNDS]   (default 20; FILE.deep.exr is checked too when present)
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "core/memory_budget.h"
#include "io/exr/exr_checksum.h"
#include "io/exr/exr_reader.h"
#include "io/exr/exr_verify.h"
#include "io/exr/exr_writer.h"

namespace {

double now_ms() {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

long peak_rss_kib() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss;
}

// The best of rounds runs of f, in ms: the least disturbed by the machine's other work.
template <class F>
double best_ms(int rounds, F f) {
  double best = 1e300;
  for (int r = 0; r < rounds; ++r) {
    const double start = now_ms();
    f();
    best = std::min(best, now_ms() - start);
  }
  return best;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: resume_check_cost FILE.exr [ROUNDS]\n");
    return 2;
  }
  const std::string path = argv[1];
  const int rounds = argc > 2 ? std::atoi(argv[2]) : 20;
  kiln::memory_budget budget(uint64_t(1) << 34);
  const kiln::exr_check first = kiln::check_flat_exr(path, {}, &budget);
  if (!first.problem.empty()) {
    std::fprintf(stderr, "%s: %s\n", path.c_str(), first.problem.c_str());
    return 1;
  }
  const long rss_before = peak_rss_kib();
  const double check = best_ms(rounds, [&] { kiln::check_flat_exr(path, {}, &budget); });
  const long rss_check = peak_rss_kib();
  size_t bytes = 0;
  const double whole = best_ms(rounds, [&] { bytes = kiln::read_exr(path).pixels.size(); });
  const long rss_whole = peak_rss_kib();
  std::string pixels(bytes, '\x5a');
  const double crc = best_ms(rounds, [&] {
    kiln::content_crc c;
    c.add(pixels.data(), pixels.size());
  });
  // The writer's whole cost for this file, its checksum included: under a lossy codec the file is
  // encoded twice and decoded once (io/exr/exr_writer.cpp's stored_checksum).
  const kiln::exr_image image = kiln::read_exr(path);
  const std::string copy = path + ".rewritten.exr";
  const double write = best_ms(std::max(1, rounds / 4), [&] { kiln::write_exr(copy, image); });
  std::filesystem::remove(copy);
  std::printf("file %s: %.1f MiB on disk, %.1f MiB of pixels\n", path.c_str(),
              double(std::filesystem::file_size(path)) / 1048576.0, double(bytes) / 1048576.0);
  std::printf("resume check (read every part band by band + CRC-32): %.2f ms\n", check);
  std::printf("read_exr of the whole image (the check before checksums): %.2f ms\n", whole);
  std::printf("CRC-32 of the pixels alone (the writer's cost, lossless codecs): %.2f ms\n", crc);
  std::printf("write_exr of the image, checksum included: %.2f ms\n", write);
  std::printf("peak RSS: %ld KiB before the checks, %ld KiB after them, %ld KiB after read_exr\n", rss_before,
              rss_check, rss_whole);
  const std::string deep = std::filesystem::path(path).replace_extension("").string() + ".deep.exr";
  if (std::filesystem::exists(deep)) {
    const double d = best_ms(rounds, [&] { kiln::check_deep_exr(deep, {}, &budget); });
    std::printf("deep check of %s (%.1f MiB): %.2f ms\n", deep.c_str(),
                double(std::filesystem::file_size(deep)) / 1048576.0, d);
  }
  return 0;
}
