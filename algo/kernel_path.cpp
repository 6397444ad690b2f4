#include "algo/kernel_path.hpp"

namespace depthkey {

bool cpuHasSsse3()
{
#if defined(__x86_64__) || defined(__i386__)
	static const bool has = [] {
		__builtin_cpu_init(); // may run before the constructor that does it
		return __builtin_cpu_supports("ssse3") != 0;
	}();
	return has;
#else
	return false;
#endif
}

} // namespace depthkey
