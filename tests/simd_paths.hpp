// The optimised kernel paths the bit-exact row tests compare against the C
// rows. All are built on every architecture (algo/kernel_path.hpp): where a
// path's instructions are missing its rows are the C rows (SSSE3: the SSE2
// rows on an x86 CPU without it, and for kernels with no SSSE3 rows; AVX2:
// the SSSE3 path's rows), so there the comparison holds trivially and the
// real one runs on the other machine (SSE2, SSSE3 and AVX2 natively on
// x86-64, NEON in `make ARCH=arm64 check` under qemu).
#pragma once

#include "algo/kernel_path.hpp"

namespace depthkey::simd_test {

inline constexpr KernelPath kSimdPaths[] = { KernelPath::Sse2, KernelPath::Ssse3, KernelPath::Avx2, KernelPath::Neon };
inline constexpr KernelPath kAllPaths[] = { KernelPath::C, KernelPath::Sse2, KernelPath::Ssse3, KernelPath::Avx2,
					    KernelPath::Neon };

inline const char *pathName(KernelPath path)
{
	switch (path) {
	case KernelPath::C:
		return "C";
	case KernelPath::Sse2:
		return "SSE2";
	case KernelPath::Ssse3:
		return "SSSE3";
	case KernelPath::Avx2:
		return "AVX2";
	case KernelPath::Neon:
		return "NEON";
	}
	return "?";
}

} // namespace depthkey::simd_test
