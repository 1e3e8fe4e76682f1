// libFuzzer target: kiln's scan of an OpenColorIO config (io/colour/module/ocio_config_text.h)
// against OpenColorIO's own reading of the same bytes. The scan bounds what OpenColorIO may spend
// reading a config, so for every input OpenColorIO reads, the scan must refuse it or count at least
// the entries OpenColorIO added; a shortfall aborts (a finding), as does a crash or a sanitizer
// report. Inputs past 64 KiB are skipped: OpenColorIO's quadratic reading would slow the search.
#include <OpenColorIO/OpenColorIO.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>

#include "io/colour/module/ocio_added_entries.h"
#include "io/colour/module/ocio_config_text.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size > (size_t(64) << 10)) return 0;
  namespace OCIO = OCIO_NAMESPACE;
  static const bool quiet = (OCIO::SetLoggingLevel(OCIO::LOGGING_LEVEL_NONE), true);
  (void)quiet;
  const std::string text(reinterpret_cast<const char*>(data), size);
  const kiln::colour_module::config_text_shape shape = kiln::colour_module::scan_config_text(text);
  if (!shape.refusal.empty()) return 0;
  OCIO::ConstConfigRcPtr cfg;
  try {
    std::istringstream in(text);
    cfg = OCIO::Config::CreateFromStream(in);
  } catch (const std::exception&) {
    return 0;  // not a config OpenColorIO reads: nothing to hold the count to
  }
  const uint64_t added = kiln::colour_module::ocio_added_entries(*cfg);
  if (shape.entries < added) {
    std::fprintf(stderr, "scan counted %llu entries, OpenColorIO added %llu\n",
                 static_cast<unsigned long long>(shape.entries), static_cast<unsigned long long>(added));
    std::abort();
  }
  return 0;
}
