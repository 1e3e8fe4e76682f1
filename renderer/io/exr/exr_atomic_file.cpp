#include "io/exr/exr_atomic_file.h"

#include <exception>

#include "core/error.h"
#include "io/exr/atomic_write.h"
#include "io/exr/exr_file_stream.h"
#include "io/exr/exr_message.h"
#include "io/exr/exr_threads.h"

namespace kiln {

void write_exr_atomically(const std::string& path, const std::string& what,
                          const std::function<void(Imf::OStream&)>& write, const std::atomic<bool>* cancel) {
  use_exr_threads();
  write_atomically(
      path, what,
      [&](const temporary_file& temporary) -> std::string {
        exr_file_stream stream(temporary.fd, temporary.path);
        if (!stream.error().empty()) return stream.error();
        try {
          // The files' destructors write the offset tables; a failure there reaches only the stream.
          write(stream);
        } catch (const error& e) {
          stream.close();
          if (e.kind() != error_kind::interrupted) throw;
          throw error(error_kind::interrupted, path, "", "interrupted while writing, nothing written");
        } catch (const std::exception& e) {
          const std::string reason =
              stream.error().empty() ? exr_message(e.what(), temporary.path) : stream.error();
          stream.close();
          return reason;
        }
        return stream.close();
      },
      cancel);
}

}  // namespace kiln
