#include "io/exr/exr_threads.h"

#include <OpenEXR/ImfThreading.h>

#include <mutex>
#include <thread>

namespace kiln {

void use_exr_threads() {
  static std::once_flag once;
  std::call_once(once,
                 [] { Imf::setGlobalThreadCount(int(std::max(1u, std::thread::hardware_concurrency()))); });
}

}  // namespace kiln
