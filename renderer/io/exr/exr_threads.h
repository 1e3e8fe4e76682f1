// OpenEXR's own worker threads, which compress and decompress a file's chunks in parallel. Inside
// io/exr only.
#pragma once

namespace kiln {

// Gives OpenEXR one worker thread per core, once per process (what OpenImageIO set up for it
// before). EXR reads and writes happen between renders, so they do not compete with the render's
// TBB threads.
void use_exr_threads();

}  // namespace kiln
