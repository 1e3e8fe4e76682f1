#include "io/exr/exr_threads.h"

#include <OpenEXR/ImfThreading.h>

#include <mutex>

namespace kiln {

void use_exr_threads() {
  static std::once_flag once;
  std::call_once(once, [] { Imf::setGlobalThreadCount(0); });
}

}  // namespace kiln
