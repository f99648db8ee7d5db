#pragma once
// Included first in every translation unit by GCC (CMakeLists.txt: -include), so that the
// x86 intrinsics headers are read here, inside a diagnostic push/pop, before anything else.
//
// Why: GCC 12 reports -Wmaybe-uninitialized and -Wuninitialized inside its own avx512fintrin.h
// (`__m512 __Y = __Y;` in _mm512_undefined_ps and friends, GCC bug 105593, fixed in GCC 13)
// whenever Eigen's AVX-512 code is inlined: about 1 200 warnings on an AVX-512 machine for a
// build of rlrun, a wall of text on a new user's first command (issue 24). The warning's
// location is the line in avx512fintrin.h, and GCC applies `#pragma GCC diagnostic` by
// location: ignoring the two warnings for the lines of the intrinsics headers only keeps them
// for every line of rlrun's own code (tests/core/test_quiet_intrinsics.cpp compiles a real
// maybe-uninitialized read and checks the warning still comes, and Eigen code that warns
// without this header and must not with it).
#if defined(__GNUC__) && !defined(__clang__) && (defined(__x86_64__) || defined(__i386__))
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#pragma GCC diagnostic ignored "-Wuninitialized"
#include <immintrin.h>
#pragma GCC diagnostic pop
#endif
