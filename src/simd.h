/* simd.h - the SSE2 intrinsics the SIMD lessons are written in, on any CPU:
 * native on x86-64, translated by SIMDe (header-only, Debian's
 * libsimde-dev) elsewhere, e.g. to NEON on ARM64. */
#ifndef TRISTEP_SIMD_H
#define TRISTEP_SIMD_H
#if defined(__SSE2__) && !defined(TRISTEP_SIMDE)
#include <emmintrin.h>
#else
#define SIMDE_ENABLE_NATIVE_ALIASES
#include <simde/x86/sse2.h>
#endif
#endif
