// DEPTHKEY_FORCE_C selects the plain C rows; unset or "0", the best path.
#include "hal/kernel_path_env.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

using namespace depthkey;

TEST(KernelPath, ForceCEnvironmentVariableSelectsTheCRows)
{
	const char *saved = std::getenv("DEPTHKEY_FORCE_C");
	std::string restore = saved ? saved : "";
	unsetenv("DEPTHKEY_FORCE_C");
	EXPECT_EQ(kernelPathFromEnvironment(), bestKernelPath());
	setenv("DEPTHKEY_FORCE_C", "1", 1);
	EXPECT_EQ(kernelPathFromEnvironment(), KernelPath::C);
	setenv("DEPTHKEY_FORCE_C", "0", 1);
	EXPECT_EQ(kernelPathFromEnvironment(), bestKernelPath());
	if (saved)
		setenv("DEPTHKEY_FORCE_C", restore.c_str(), 1);
	else
		unsetenv("DEPTHKEY_FORCE_C");
#if defined(__x86_64__)
	EXPECT_EQ(bestKernelPath(), cpuHasAvx2() ? KernelPath::Avx2 : cpuHasSsse3() ? KernelPath::Ssse3 : KernelPath::Sse2)
		<< "SSE2 is the x86-64 baseline, SSSE3 and AVX2 where the CPU has them";
#elif defined(__aarch64__)
	EXPECT_EQ(bestKernelPath(), KernelPath::Neon) << "NEON is the AArch64 baseline";
#endif
}
