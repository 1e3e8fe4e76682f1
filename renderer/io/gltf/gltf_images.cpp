#include "io/gltf/gltf_images.h"

#include <fcntl.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#include <unistd.h>

#include <cstdio>
#include <exception>

#include "io/image_codecs/codecs_loader.h"

namespace kiln::gltf_internal {
namespace {

// libpng reports decoding errors by printing "libpng error: ..." to stderr itself before
// OpenImageIO turns them into an error string; kiln reports that string as its one line. While
// a batch of images decodes, fd 2 points at /dev/null. Nothing else runs during loading, so
// nothing else loses output meanwhile.
class silenced_stderr {
 public:
  silenced_stderr() {
    std::fflush(stderr);
    saved_ = ::dup(STDERR_FILENO);
    const int null = ::open("/dev/null", O_WRONLY | O_CLOEXEC);
    if (saved_ >= 0 && null >= 0) ::dup2(null, STDERR_FILENO);
    if (null >= 0) ::close(null);
  }
  ~silenced_stderr() {
    std::fflush(stderr);
    if (saved_ >= 0) {
      ::dup2(saved_, STDERR_FILENO);
      ::close(saved_);
    }
  }
  silenced_stderr(const silenced_stderr&) = delete;
  silenced_stderr& operator=(const silenced_stderr&) = delete;

 private:
  int saved_ = -1;
};

}  // namespace

std::vector<image> decode_images(const std::vector<encoded_image>& batch, const std::string& file,
                                 uint64_t max_texels, int threads) {
  if (batch.empty()) return {};
  const image_codecs& codecs = load_image_codecs("textures need");
  std::vector<image> images(batch.size());
  // Each image records its own failure; the first in batch order is reported, so the message
  // does not depend on which thread finished first.
  std::vector<std::exception_ptr> failures(batch.size());
  {
    silenced_stderr quiet;
    tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
    arena.execute([&] {
      // One image per task: images differ in size by orders of magnitude.
      tbb::parallel_for(size_t(0), batch.size(), [&](size_t i) {
        const encoded_image& in = batch[i];
        try {
          images[i] = codecs.decode(in.data, in.size, in.name, file, in.where, max_texels);
        } catch (...) {
          failures[i] = std::current_exception();
        }
      });
    });
  }
  for (const std::exception_ptr& failure : failures)
    if (failure) std::rethrow_exception(failure);
  return images;
}

}  // namespace kiln::gltf_internal
