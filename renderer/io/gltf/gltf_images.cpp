#include "io/gltf/gltf_images.h"

#include <fcntl.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#include <unistd.h>

#include <cstdio>
#include <exception>
#include <optional>

#include "core/error.h"
#include "io/gltf/gltf_memory.h"
#include "io/gltf/image_header.h"
#include "io/image_codecs/codecs_loader.h"
#include "io/image_codecs/direct_decode.h"

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

// Refuses an image whose own header is not one kiln takes, has no size, declares more than
// max_texels or more than its data can hold, before any decoder (or the module holding them) is
// touched.
image_header checked_header(const encoded_image& in, const std::string& file, uint64_t max_texels) {
  const image_header h = read_image_header(in.data, in.size);
  if (h.format.empty()) throw input_error(file, in.where, "image data is not PNG, JPEG, WebP, GIF or BMP");
  if (h.width == 0)
    throw input_error(file, in.where,
                      "cannot read the image size from its " + h.format + " header (cut short or corrupt)");
  if (h.width > max_texels / h.height)  // width · height > max_texels, without overflow
    throw input_error(file, in.where,
                      "image is " + std::to_string(h.width) + "x" + std::to_string(h.height) +
                          " texels, over the limit of " + std::to_string(max_texels) + " (--max-texels)");
  if (const std::string problem = image_data_problem(in.data, in.size, h); !problem.empty())
    throw input_error(file, in.where, problem);
  return h;
}

}  // namespace

std::vector<image> decode_images(const std::vector<encoded_image>& batch, const std::string& file,
                                 uint64_t max_texels, int threads, memory_budget* memory) {
  if (batch.empty()) return {};
  std::vector<image_header> headers;
  for (const encoded_image& in : batch) headers.push_back(checked_header(in, file, max_texels));
  image_bytes need;
  for (size_t i = 0; i < batch.size(); ++i) {
    const image_bytes b =
        decoded_image_bytes(batch[i].data, batch[i].size, headers[i].width, headers[i].height);
    need.kept += b.kept;
    need.decoding += b.decoding;
  }
  charge_memory(memory, need.kept, file, "the decoded textures");
  memory_charge decoding(memory);
  decoding.add(need.decoding, file, "the decoded textures and their decoders' buffers");
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
          // 8-bit PNG and JPEG decode here; the module (opened once, the first time an image
          // needs it) decodes the rest and words every refusal.
          if (std::optional<image> direct = decode_directly(in.data, in.size, max_texels)) {
            images[i] = std::move(*direct);
            images[i].name = in.name;
          } else {
            images[i] = load_image_codecs("textures need")
                            .decode(in.data, in.size, in.name, file, in.where, max_texels);
          }
          // GIF frames may differ from the logical screen; every other format decodes to its header's size.
          const image_header& h = headers[i];
          if (h.format != "GIF" &&
              (uint64_t(images[i].width) != h.width || uint64_t(images[i].height) != h.height))
            throw input_error(file, in.where,
                              "image decodes to " + std::to_string(images[i].width) + "x" +
                                  std::to_string(images[i].height) + " texels, its " + h.format +
                                  " header says " + std::to_string(h.width) + "x" + std::to_string(h.height));
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
