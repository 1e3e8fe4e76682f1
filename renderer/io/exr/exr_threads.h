// OpenEXR's own worker threads. Inside io/exr only.
#pragma once

namespace kiln {

// Runs OpenEXR without its global worker pool (compression on the calling thread), once per
// process. One thread per core measured no faster on the 2-core machine (a 1920x1080, 52-channel
// write), and with the pool LeakSanitizer found header attributes still held by it at exit in
// runs under load.
void use_exr_threads();

}  // namespace kiln
