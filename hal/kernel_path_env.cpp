#include "hal/kernel_path_env.hpp"

#include <cstdlib>
#include <cstring>

namespace depthkey {

KernelPath kernelPathFromEnvironment()
{
	const char *force = std::getenv("DEPTHKEY_FORCE_C");
	if (force && *force && std::strcmp(force, "0") != 0)
		return KernelPath::C;
	return bestKernelPath();
}

} // namespace depthkey
