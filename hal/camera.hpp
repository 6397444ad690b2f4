// A camera as the daemon sees it, whatever the backend (simulated, SR-2 over
// USB, V4L2): it is started on the event loop, delivers frames through a
// callback and reports its state. A backend that loses its device reports
// Lost, keeps retrying by itself, and reports Streaming when it is back.
#pragma once

#include "algo/frames.hpp"
#include "hal/event_loop.hpp"

#include <functional>
#include <string>

namespace depthkey {

enum class DeviceState {
	Stopped,
	Streaming,
	Lost, // unplugged, stalled or failing; the backend retries with backoff
};

const char *deviceStateName(DeviceState state);

struct DeviceStatus {
	DeviceState state = DeviceState::Stopped;
	int error = 0;          // negative errno of the last failure, 0 if none
	std::string detail;     // what failed and where, for the journal
	uint64_t droppedFrames = 0; // short, corrupt or error-flagged frames refused

	// Sets state, error and detail; true when any of them changed, i.e. when
	// the daemon should hear about it (the drop counter alone does not count).
	bool set(DeviceState newState, int newError, const std::string &newDetail)
	{
		bool changed = newState != state || newError != error || newDetail != detail;
		state = newState;
		error = newError;
		detail = newDetail;
		return changed;
	}
};

template<typename Frame>
class Camera
{
public:
	using FrameHandler = std::function<void(const Frame &)>;
	using StatusHandler = std::function<void(const DeviceStatus &)>;

	virtual ~Camera() = default;

	// A name for logs and the journal's DEVICE= field, e.g. "sim-colour".
	virtual std::string name() const = 0;

	// Starts streaming. A negative errno means it could not even try (bad
	// parameters); a device that is merely absent starts in the Lost state.
	virtual int start(EventLoop &loop, FrameHandler onFrame, StatusHandler onStatus) = 0;
	virtual void stop() = 0;

	virtual DeviceStatus status() const = 0;

	// Whether frames come at the device's own rate whether or not they are
	// taken (a live camera): a daemon too slow for them must shed some
	// (daemon/keying_worker.hpp). False for a source that waits for the
	// daemon (a replay not in real time), whose every frame is keyed.
	virtual bool freeRunning() const { return true; }

	// Where the camera may make its next frame: storage of the handler's (the
	// daemon lends the pairing ring's free slot), so that the frame is not
	// copied there and no frame-sized buffer of the camera's own is kept
	// beside the ring (issue 15). Asked just before each frame is made; null:
	// make it in the camera's own buffer. The frame handed to onFrame is then
	// the lent one. A backend may ignore it (the default) and make every
	// frame in its own buffer; set before start().
	using FrameLender = std::function<Frame *()>;
	virtual void lendFrames(FrameLender lender) { (void)lender; }
};

using ColourCamera = Camera<ColourFrame>;
using DepthCamera = Camera<DepthFrame>;

} // namespace depthkey
