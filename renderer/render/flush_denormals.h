// Flush-to-zero and denormals-are-zero for the SSE unit of the calling thread, for one scope.
// Embree asks for both in every thread that traces (denormal operands slow SSE arithmetic by
// ~100x), and shading never relies on values below FLT_MIN. The previous MXCSR is restored on
// exit, so a thread that joins a render (the caller of task_arena::execute) leaves it unchanged.
#pragma once

#include <pmmintrin.h>
#include <xmmintrin.h>

namespace kiln {

class scoped_flush_denormals {
 public:
  scoped_flush_denormals() : saved_(_mm_getcsr()) {
    _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
    _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
  }
  ~scoped_flush_denormals() { _mm_setcsr(saved_); }
  scoped_flush_denormals(const scoped_flush_denormals&) = delete;
  scoped_flush_denormals& operator=(const scoped_flush_denormals&) = delete;

 private:
  unsigned saved_;
};

}  // namespace kiln
