#include "hal/camera.hpp"

namespace depthkey {

const char *deviceStateName(DeviceState state)
{
	switch (state) {
	case DeviceState::Stopped:
		return "stopped";
	case DeviceState::Streaming:
		return "streaming";
	case DeviceState::Lost:
		return "lost";
	}
	return "unknown";
}

} // namespace depthkey
