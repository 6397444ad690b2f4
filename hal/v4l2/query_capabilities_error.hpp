// What VIDIOC_QUERYCAP's failure says about a node. A kernel answers ENOTTY
// ("no such ioctl for this file") on a node that is no V4L2 device, and the
// callers report that as "not a V4L2 device". qemu-user (the arm64 build's
// test bed, docs/arm64.md) answers ENOSYS instead for every ioctl it does not
// emulate, /dev/null's QUERYCAP among them, so the same node would fail for
// another reason there. Both mean the node does not implement V4L2.
#pragma once

#include <cerrno>

namespace depthkey {

constexpr int queryCapabilitiesError(int ret)
{
	return ret == -ENOSYS ? -ENOTTY : ret;
}

} // namespace depthkey
