// DEPTHKEY_FORCE_C=1 in the environment forces the plain C row kernels (to
// compare against the SSE2 ones on a running box, or to rule them out when
// chasing a bug); anything else, or unset, selects the best this build has.
#pragma once

#include "algo/kernel_path.hpp"

namespace depthkey {

KernelPath kernelPathFromEnvironment();

} // namespace depthkey
