// Which implementation of the per-pixel row kernels runs (libyuv style: every
// kernel has a plain C++ reference, <Op>Row_C, and optimised variants beside
// it, <Op>Row_SSE2 and <Op>Row_NEON). The choice is made once per call of a whole-image
// function, never per pixel, and is the caller's: algo/ reads no environment
// (hal/kernel_path_env.hpp reads DEPTHKEY_FORCE_C for the daemon and tools).
//
// SSE2 is the x86-64 baseline and NEON (Advanced SIMD) the AArch64 one, so
// neither needs a CPU check; nothing newer is used (the box and QEMU TCG
// have no SSE4/AVX or SVE guarantee). Each variant is built on every
// architecture: where its instructions are missing it is the C row, so a
// test can name any path anywhere.
#pragma once

namespace depthkey {

enum class KernelPath {
	C,     // the plain reference rows
	Sse2,  // SSE2 rows where they exist, the C rows elsewhere
	Neon,  // NEON rows (AArch64), the C rows elsewhere
};

// The fastest path this build has.
constexpr KernelPath bestKernelPath()
{
#if defined(__SSE2__)
	return KernelPath::Sse2;
#elif defined(__ARM_NEON)
	return KernelPath::Neon;
#else
	return KernelPath::C;
#endif
}

} // namespace depthkey
