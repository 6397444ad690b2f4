// The SwissRanger SR-2 over libusb-1.0, asynchronous and driven by the
// daemon's event loop (UsbEventBridge): one transfer at a time walks the
// protocol (register writes, frame request, bulk read), each with a timeout,
// so a stalled camera never blocks anything else. A lost camera (unplug,
// transfer error, timeout, persistent corruption) is reported Lost, closed
// and re-opened with backoff; a hotplug arrival retries at once.
#pragma once

#include "hal/camera.hpp"
#include "hal/reconnect_backoff.hpp"
#include "hal/sr2/sr2_usb_device.hpp"
#include "hal/usb/usb_event_bridge.hpp"
#include "settings/settings.hpp"

#include <deque>
#include <libusb.h>
#include <vector>

namespace depthkey {

class Sr2Camera : public DepthCamera
{
public:
	explicit Sr2Camera(const DepthCameraSettings &settings) : settings_(settings) {}
	~Sr2Camera() override { stop(); }

	std::string name() const override { return "sr2"; }
	int start(EventLoop &loop, FrameHandler onFrame, StatusHandler onStatus) override;
	void stop() override;
	DeviceStatus status() const override { return status_; }

private:
	enum class Phase { Stopped, Closed, Running, Closing };

	void tryOpen();
	void next();
	void writeRegister(const Sr2RegisterWrite &write);
	void requestFrame();
	void readFrame();
	int submit(libusb_transfer *transfer);
	void onTransferDone(libusb_transfer *transfer);
	void onFrameData(size_t length);
	void fail(int error, const std::string &detail);
	void finishClose();
	void queueRegisterWrites();
	void setStatus(DeviceState state, int error, const std::string &detail);
	int registerHotplug();
	void onHotplug(libusb_device *device, bool arrived);

	static void transferCallback(libusb_transfer *transfer);
	static int hotplugCallback(libusb_context *, libusb_device *device,
				   libusb_hotplug_event event, void *user);

	DepthCameraSettings settings_;
	EventLoop *loop_ = nullptr;
	FrameHandler onFrame_;
	StatusHandler onStatus_;
	DeviceStatus status_;

	UsbEventBridge usb_;
	libusb_device_handle *handle_ = nullptr;
	Sr2Endpoints endpoints_;
	libusb_transfer *control_ = nullptr, *bulk_ = nullptr, *register_ = nullptr;
	libusb_transfer *inFlight_ = nullptr; // the protocol is strictly one at a time
	std::vector<uint8_t> controlBuffer_, bulkBuffer_, registerBuffer_;
	int hotplugHandle_ = -1;

	Phase phase_ = Phase::Stopped;
	std::deque<Sr2RegisterWrite> pendingWrites_;
	ReconnectBackoff backoff_;
	EventSource retryTimer_, pacer_, closer_;
	uint64_t lastRequestUs_ = 0;
	int integrationTime_ = 0;
	int badInRow_ = 0;
	int readTimeoutsInRow_ = 0;
	bool streaming_ = false;
	DepthFrame frame_;
};

} // namespace depthkey
