// One EXR file written atomically through OpenEXR: the flat writer's and the deep writer's common
// tail (a checked file stream, the temporary file renamed into place). Inside io/exr only.
#pragma once

#include <OpenEXR/ImfIO.h>

#include <atomic>
#include <functional>
#include <string>

namespace kiln {

// Calls write(stream) on a stream to a temporary file beside path, then renames it into place
// (io/exr/atomic_write.h). `what` names the file in errors ("EXR", "deep EXR"). An OpenEXR failure
// becomes kiln::error (io) naming path; an interrupted write (cancel) leaves nothing behind.
void write_exr_atomically(const std::string& path, const std::string& what,
                          const std::function<void(Imf::OStream&)>& write, const std::atomic<bool>* cancel);

}  // namespace kiln
