// KILN_CHECK: an invariant check that stays on in every build type (tests rely on it).
// A failed check is a bug in kiln, not bad input: it aborts with the expression and location.
#pragma once

#include <cstdio>
#include <cstdlib>

#define KILN_CHECK(condition)                                                                             \
  do {                                                                                                    \
    if (!(condition)) {                                                                                   \
      std::fprintf(stderr, "kiln: internal check failed: %s at %s:%d\n", #condition, __FILE__, __LINE__); \
      std::abort();                                                                                       \
    }                                                                                                     \
  } while (false)
