#include "hal/sr2/sr2_camera.hpp"

#include "hal/sr2/sr2_frame_parser.hpp"
#include "hal/sr2/sr2_protocol.hpp"
#include "hal/sr2/sr2_usb_device.hpp"

#include <cerrno>
#include <libusb.h>

namespace depthkey {

namespace {

// Isolated bad frames are dropped. This many refused frames in a row and the
// camera counts as lost, and its registers are written again on the same
// handle: a camera that reset itself and lost them sends frames in the wrong
// mode. Only kBadFramesBeforeReopen in a row (some five seconds) re-open
// it, in case the handle itself is out of step. Re-opening at the tenth cost
// the HIL suite's SR-2 its 2 s limit in CI (sr2-short-frames 2.063 s): a
// camera sending short frames was re-opened every 1.5 s, and when it
// recovered the daemon was inside a close/back-off/open cycle.
constexpr int kBadFramesBeforeRewrite = 10;
constexpr int kBadFramesBeforeReopen = 50;
// A frame read that times out is reported at once (the camera is lost), and
// the frame requested again on the same handle; only this many in a row
// (some ten seconds of silence) re-open the camera, in case the handle
// itself went bad. A camera that stalled and resumes answers the next
// request. Re-opening sooner cost the HIL suite's SR-2 its 2 s limit twice
// in CI: after 3 timeouts the daemon was inside a re-open cycle (close,
// back-off, open, register writes, a request the stalled camera dropped)
// when the emulator resumed, and took 1.1-1.4 s more. A camera that reset
// itself and lost its registers sends frames in the wrong mode: those are
// refused as bad, and ten in a row write them again.
constexpr int kReadTimeoutsBeforeReopen = 20;
// stop() waits this long for a cancelled transfer before giving up on it.
constexpr int kStopWaitMs = 3000;

} // namespace

int Sr2Camera::start(EventLoop &loop, FrameHandler onFrame, StatusHandler onStatus)
{
	if (phase_ != Phase::Stopped)
		return -EBUSY;
	loop_ = &loop;
	onFrame_ = std::move(onFrame);
	onStatus_ = std::move(onStatus);
	int ret = usb_.open(loop);
	if (ret < 0)
		return ret;
	control_ = libusb_alloc_transfer(0);
	bulk_ = libusb_alloc_transfer(0);
	register_ = libusb_alloc_transfer(0);
	if (!control_ || !bulk_ || !register_) {
		stop();
		return -ENOMEM;
	}
	controlBuffer_.assign(LIBUSB_CONTROL_SETUP_SIZE, 0);
	bulkBuffer_.assign(sr2::kReadBytes, 0);
	registerBuffer_.assign(2, 0);
	frame_.sequence = 0;
	integrationTime_ = settings_.integrationTime;
	registerHotplug(); // without udev, transfer errors and retries still find it
	phase_ = Phase::Closed;
	tryOpen();
	return 0;
}

void Sr2Camera::stop()
{
	if (phase_ == Phase::Stopped)
		return;
	phase_ = Phase::Stopped;
	retryTimer_.reset();
	pacer_.reset();
	closer_.reset();
	if (inFlight_)
		libusb_cancel_transfer(inFlight_);
	for (int waited = 0; inFlight_ && waited < kStopWaitMs; waited += 100)
		usb_.handleEventsBlocking(100);
	closeSr2(handle_);
	handle_ = nullptr;
	if (hotplugHandle_ >= 0)
		libusb_hotplug_deregister_callback(usb_.context(), hotplugHandle_);
	hotplugHandle_ = -1;
	// A transfer libusb still holds (it never completed) is leaked rather
	// than freed under it.
	for (libusb_transfer *t : { control_, bulk_, register_ })
		if (t && t != inFlight_)
			libusb_free_transfer(t);
	control_ = bulk_ = register_ = inFlight_ = nullptr;
	usb_.close();
	status_ = { DeviceState::Stopped, 0, "", status_.droppedFrames };
}

void Sr2Camera::setStatus(DeviceState state, int error, const std::string &detail)
{
	if (status_.set(state, error, detail) && onStatus_)
		onStatus_(status_);
}

void Sr2Camera::tryOpen()
{
	if (phase_ != Phase::Closed)
		return;
	std::string detail;
	int ret = openSr2(usb_.context(), settings_.usbPath, handle_, endpoints_, detail);
	if (ret < 0) {
		setStatus(DeviceState::Lost, ret, detail);
		loop_->addTimer(backoff_.nextDelayUs(), [this] { tryOpen(); }, retryTimer_);
		return;
	}
	phase_ = Phase::Running;
	streaming_ = false;
	badInRow_ = 0;
	readTimeoutsInRow_ = 0;
	queueRegisterWrites();
	next();
}

// The registers the daemon sets, in the order an open writes them.
void Sr2Camera::queueRegisterWrites()
{
	pendingWrites_.clear();
	pendingWrites_.push_back({ sr2::kRegOutputMode.address, sr2::kOutputDistanceIntensityAmplitude });
	pendingWrites_.push_back({ sr2::kRegIntegrationTime.address, integrationTime_ });
	for (const Sr2RegisterWrite &w : settings_.sr2Registers)
		pendingWrites_.push_back(w);
}

// The protocol's one step at a time: pending register writes first, then the
// next frame request, paced at the configured frame rate.
void Sr2Camera::next()
{
	if (phase_ != Phase::Running)
		return;
	if (!pendingWrites_.empty()) {
		Sr2RegisterWrite w = pendingWrites_.front();
		pendingWrites_.pop_front();
		writeRegister(w);
		return;
	}
	uint64_t now = loop_->nowUs();
	uint64_t due = lastRequestUs_ + 1000000u / settings_.fps;
	// Overdue (the loop came late): request at once. A timer would wait a
	// turn of the loop more, and on a box that keys slowly each turn can
	// wait a keyed frame: three such waits a depth frame (timer, request,
	// read) held the HIL VM's SR-2 at 1-2 of its 10 fps.
	if (due <= now) {
		pacer_.reset();
		requestFrame();
		return;
	}
	loop_->addTimer(due - now, [this] { requestFrame(); }, pacer_);
}

int Sr2Camera::submit(libusb_transfer *transfer)
{
	int ret = libusb_submit_transfer(transfer);
	if (ret < 0) {
		fail(usbErrno(ret), std::string("cannot submit transfer: ") + libusb_error_name(ret));
		return ret;
	}
	inFlight_ = transfer;
	usb_.handleEvents(); // schedules the transfer's timeout
	return 0;
}

void Sr2Camera::writeRegister(const Sr2RegisterWrite &write)
{
	registerBuffer_[0] = static_cast<uint8_t>(write.address);
	registerBuffer_[1] = static_cast<uint8_t>(write.value);
	libusb_fill_bulk_transfer(register_, handle_, endpoints_.registersOut,
				  registerBuffer_.data(), 2, transferCallback, this,
				  settings_.timeoutMs);
	submit(register_);
}

void Sr2Camera::requestFrame()
{
	lastRequestUs_ = loop_->nowUs();
	libusb_fill_control_setup(controlBuffer_.data(), sr2::kRequestTypeVendorOut,
				  sr2::kRequestFrame, 0, 0, 0);
	libusb_fill_control_transfer(control_, handle_, controlBuffer_.data(), transferCallback,
				     this, settings_.timeoutMs);
	submit(control_);
}

void Sr2Camera::readFrame()
{
	libusb_fill_bulk_transfer(bulk_, handle_, endpoints_.framesIn, bulkBuffer_.data(),
				  static_cast<int>(bulkBuffer_.size()), transferCallback, this,
				  settings_.timeoutMs);
	submit(bulk_);
}

void Sr2Camera::transferCallback(libusb_transfer *transfer)
{
	static_cast<Sr2Camera *>(transfer->user_data)->onTransferDone(transfer);
}

void Sr2Camera::onTransferDone(libusb_transfer *t)
{
	inFlight_ = nullptr;
	if (phase_ == Phase::Closing) {
		finishClose();
		return;
	}
	if (phase_ != Phase::Running)
		return; // stopping: stop() only waits for inFlight_
	const char *what = t == bulk_ ? "frame read" : t == control_ ? "frame request" : "register write";
	switch (t->status) {
	case LIBUSB_TRANSFER_COMPLETED:
		break;
	case LIBUSB_TRANSFER_OVERFLOW: // more data than one frame: refuse it, go on
		status_.droppedFrames++;
		return next();
	case LIBUSB_TRANSFER_TIMED_OUT: {
		std::string detail = std::string(what) + " timed out after " + std::to_string(settings_.timeoutMs) +
				     " ms (stalled)";
		if (t != bulk_ || ++readTimeoutsInRow_ >= kReadTimeoutsBeforeReopen)
			return fail(-ETIMEDOUT, detail);
		streaming_ = false;
		setStatus(DeviceState::Lost, -ETIMEDOUT, detail);
		return next();
	}
	case LIBUSB_TRANSFER_NO_DEVICE:
		return fail(-ENODEV, std::string("unplugged during ") + what);
	case LIBUSB_TRANSFER_STALL:
		return fail(-EPIPE, std::string(what) + ": endpoint stalled");
	default:
		return fail(-EIO, std::string(what) + " failed");
	}
	if (t == control_)
		readFrame();
	else if (t == bulk_)
		onFrameData(static_cast<size_t>(t->actual_length));
	else
		next();
}

void Sr2Camera::onFrameData(size_t length)
{
	Sr2FrameStats stats;
	Sr2FrameCheck check = parseSr2Frame(bulkBuffer_.data(), length, settings_.minMm,
					    settings_.maxMm, frame_, stats);
	if (check != Sr2FrameCheck::Ok) {
		status_.droppedFrames++;
		if (++badInRow_ % kBadFramesBeforeRewrite != 0)
			return next();
		// One text for the rewrite and the re-open: a camera that stays bad
		// is logged once, again only when what is wrong changes.
		std::string detail = std::to_string(kBadFramesBeforeRewrite) + " bad frames in a row (last " +
				     sr2FrameCheckName(check) + ", " + std::to_string(length) + " bytes)";
		if (badInRow_ >= kBadFramesBeforeReopen)
			return fail(-EBADMSG, detail);
		streaming_ = false;
		setStatus(DeviceState::Lost, -EBADMSG, detail);
		queueRegisterWrites();
		return next();
	}
	badInRow_ = 0;
	readTimeoutsInRow_ = 0;
	if (!streaming_) {
		streaming_ = true;
		backoff_.reset();
		setStatus(DeviceState::Streaming, 0, "");
	}
	frame_.timestampNs = loop_->nowUs() * 1000u; // the SR-2 sends no timestamp
	frame_.sequence++;
	onFrame_(frame_);
	if (settings_.autoIntegration && phase_ == Phase::Running) {
		int t = sr2NextIntegrationTime(integrationTime_, stats.meanIntensity,
					       settings_.intensityLow, settings_.intensityHigh);
		if (t != integrationTime_) {
			integrationTime_ = t;
			pendingWrites_.push_back({ sr2::kRegIntegrationTime.address, t });
		}
	}
	next();
}

void Sr2Camera::fail(int error, const std::string &detail)
{
	if (phase_ != Phase::Running)
		return;
	phase_ = Phase::Closing;
	pacer_.reset();
	setStatus(DeviceState::Lost, error, detail);
	if (inFlight_)
		libusb_cancel_transfer(inFlight_); // completes later, then finishClose()
	else
		finishClose();
}

// Closing the handle is deferred out of libusb's event handling (where the
// transfer callbacks and hotplug callbacks run).
void Sr2Camera::finishClose()
{
	loop_->addTimer(0, [this] {
		closeSr2(handle_);
		handle_ = nullptr;
		phase_ = Phase::Closed;
		loop_->addTimer(backoff_.nextDelayUs(), [this] { tryOpen(); }, retryTimer_);
	}, closer_);
}

int Sr2Camera::registerHotplug()
{
	if (!libusb_has_capability(LIBUSB_CAP_HAS_HOTPLUG))
		return -ENOTSUP;
	int events = LIBUSB_HOTPLUG_EVENT_DEVICE_ARRIVED | LIBUSB_HOTPLUG_EVENT_DEVICE_LEFT;
	libusb_hotplug_callback_handle handle;
	int ret = libusb_hotplug_register_callback(usb_.context(), events, LIBUSB_HOTPLUG_NO_FLAGS,
						   sr2::kVendorId, sr2::kProductId,
						   LIBUSB_HOTPLUG_MATCH_ANY, hotplugCallback, this,
						   &handle);
	if (ret < 0)
		return usbErrno(ret);
	hotplugHandle_ = handle;
	return 0;
}

int Sr2Camera::hotplugCallback(libusb_context *, libusb_device *device,
			       libusb_hotplug_event event, void *user)
{
	static_cast<Sr2Camera *>(user)->onHotplug(device,
						  event == LIBUSB_HOTPLUG_EVENT_DEVICE_ARRIVED);
	return 0; // stay registered
}

void Sr2Camera::onHotplug(libusb_device *device, bool arrived)
{
	if (!arrived) {
		if (handle_ && libusb_get_device(handle_) == device)
			fail(-ENODEV, "unplugged from " + usbPortPath(device));
		return;
	}
	// Retry now rather than at the end of the backoff, outside libusb's
	// event handling.
	if (phase_ == Phase::Closed)
		loop_->addTimer(0, [this] { tryOpen(); }, retryTimer_);
}

} // namespace depthkey
