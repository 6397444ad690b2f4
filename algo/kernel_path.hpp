// Which implementation of the per-pixel row kernels runs (libyuv style: every
// kernel has a plain C++ reference, <Op>Row_C, and optimised variants beside
// it, <Op>Row_SSE2, <Op>Row_SSSE3, <Op>Row_AVX2 and <Op>Row_NEON). The choice is made once per call of a whole-image
// function, never per pixel, and is the caller's: algo/ reads no environment
// (hal/kernel_path_env.hpp reads DEPTHKEY_FORCE_C for the daemon and tools).
//
// SSE2 is the x86-64 baseline and NEON (Advanced SIMD) the AArch64 one, so
// neither needs a CPU check. SSSE3 is not in the baseline (QEMU TCG's
// default CPU lacks it): its rows are compiled for it per function and run
// only where the CPU says it has it (cpuHasSsse3()); a kernel without SSSE3
// rows runs its SSE2 rows on that path (sse2Rows()). AVX2 likewise
// (cpuHasAvx2(); the box has no AVX guarantee, but where it has AVX2 the
// board warp's eight-pixel row is a third faster): a kernel without AVX2
// rows runs its SSSE3 rows, or SSE2 ones, on that path. Each variant is
// built on every architecture: where its instructions are missing it is the
// C row (SSSE3: the SSE2 row where the CPU lacks it; AVX2: the SSSE3 path's
// row), so a test can name any path anywhere.
#pragma once

namespace depthkey {

enum class KernelPath {
	C,     // the plain reference rows
	Sse2,  // SSE2 rows where they exist, the C rows elsewhere
	Ssse3, // SSSE3 rows where they exist and the CPU has SSSE3, else as Sse2
	Avx2,  // AVX2 rows where they exist and the CPU has AVX2, else as Ssse3
	Neon,  // NEON rows (AArch64), the C rows elsewhere
};

// Whether this CPU runs SSSE3 (asked once; false off x86).
bool cpuHasSsse3();
// Whether this CPU (and its OS) runs AVX2 (asked once; false off x86).
bool cpuHasAvx2();

// Whether path runs a kernel's SSE2 rows (where it has no SSSE3 ones).
constexpr bool sse2Rows(KernelPath path)
{
	return path == KernelPath::Sse2 || path == KernelPath::Ssse3 || path == KernelPath::Avx2;
}

// The fastest path this build has on this CPU.
inline KernelPath bestKernelPath()
{
#if defined(__SSE2__)
	return cpuHasAvx2() ? KernelPath::Avx2 : cpuHasSsse3() ? KernelPath::Ssse3 : KernelPath::Sse2;
#elif defined(__ARM_NEON)
	return KernelPath::Neon;
#else
	return KernelPath::C;
#endif
}

} // namespace depthkey
