#include "algo/kernel_path.hpp"

// Asked once per feature. __builtin_cpu_supports takes only a literal (so a
// macro, not a function), and for AVX2 also checks that the OS saves the
// registers; __builtin_cpu_init because this may run before the constructor
// that calls it.
#if defined(__x86_64__) || defined(__i386__)
#define DEPTHKEY_CPU_HAS(feature) (__builtin_cpu_init(), __builtin_cpu_supports(feature) != 0)
#else
#define DEPTHKEY_CPU_HAS(feature) false
#endif

namespace depthkey {

bool cpuHasSsse3()
{
	static const bool has = DEPTHKEY_CPU_HAS("ssse3");
	return has;
}

bool cpuHasAvx2()
{
	static const bool has = DEPTHKEY_CPU_HAS("avx2");
	return has;
}

} // namespace depthkey
