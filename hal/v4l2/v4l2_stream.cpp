#include "hal/v4l2/v4l2_stream.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <sys/epoll.h>

namespace depthkey {

namespace {

// Enough to keep the driver filling one while we convert another.
constexpr unsigned kBufferCount = 4;

} // namespace

std::string resolveVideoDevice(const std::string &device)
{
	return device.find('/') == std::string::npos ? "/dev/v4l/by-id/" + device : device;
}

uint32_t chooseFourcc(const std::vector<uint32_t> &wanted, const std::vector<uint32_t> &offered)
{
	for (uint32_t f : wanted)
		if (std::find(offered.begin(), offered.end(), f) != offered.end())
			return f;
	return 0;
}

int V4l2Stream::start(EventLoop &loop, V4l2StreamConfig config, BufferHandler onBuffer,
		      StatusHandler onStatus)
{
	if (config.fourccs.empty() || config.width <= 0 || config.height <= 0 || config.fps <= 0)
		return -EINVAL;
	stop();
	loop_ = &loop;
	config_ = std::move(config);
	onBuffer_ = std::move(onBuffer);
	onStatus_ = std::move(onStatus);
	stall_.setTimeout(config_.timeoutUs);
	tryOpen();
	return 0;
}

void V4l2Stream::stop()
{
	io_.reset();
	retryTimer_.reset();
	watchdog_.reset();
	device_.close();
	open_ = false;
	status_ = { DeviceState::Stopped, 0, "", status_.droppedFrames };
}

void V4l2Stream::setStatus(DeviceState state, int error, const std::string &detail)
{
	if (status_.set(state, error, detail) && onStatus_)
		onStatus_(status_);
}

void V4l2Stream::tryOpen()
{
	std::string detail;
	int ret = openDevice(detail);
	if (ret < 0) {
		device_.close();
		setStatus(DeviceState::Lost, ret, detail);
		loop_->addTimer(backoff_.nextDelayUs(), [this] { tryOpen(); }, retryTimer_);
		return;
	}
	open_ = true;
	delivered_ = false;
	stall_.arm(loop_->nowUs());
	loop_->addIo(device_.fd(), EPOLLIN, [this](uint32_t revents) { onReadable(revents); }, io_);
	loop_->addPeriodic(config_.timeoutUs / 4, [this] { onWatchdog(); }, watchdog_);
}

int V4l2Stream::openDevice(std::string &detail)
{
	std::string path = resolveVideoDevice(config_.device);
	auto failed = [&](const char *step, int ret) {
		detail = path + ": " + step + ": " + std::strerror(-ret);
		return ret;
	};
	int ret = device_.open(path);
	if (ret < 0)
		return failed("open", ret);
	uint32_t fourcc = chooseFourcc(config_.fourccs, device_.formats());
	if (!fourcc) {
		std::string wanted;
		for (uint32_t f : config_.fourccs)
			wanted += (wanted.empty() ? "" : ", ") + fourccName(f);
		detail = path + " (" + device_.card() + ") offers none of " + wanted;
		return -EINVAL;
	}
	format_ = { fourcc, config_.width, config_.height, 0, 0 };
	if ((ret = device_.setFormat(format_)) < 0)
		return failed("set format", ret);
	if (format_.fourcc != fourcc || format_.width != config_.width ||
	    format_.height != config_.height) {
		detail = path + " gives " + fourccName(format_.fourcc) + " " +
			 std::to_string(format_.width) + "x" + std::to_string(format_.height) +
			 ", the config asks " + fourccName(fourcc) + " " +
			 std::to_string(config_.width) + "x" + std::to_string(config_.height);
		return -EINVAL;
	}
	device_.setFrameRate(config_.fps); // not every driver can; it then runs at its own rate
	if ((ret = device_.allocateBuffers(kBufferCount)) < 0)
		return failed("allocate buffers", ret);
	for (int i = 0; i < ret; i++) {
		int q = device_.queueBuffer(static_cast<unsigned>(i));
		if (q < 0)
			return failed("queue buffer", q);
	}
	if ((ret = device_.streamOn()) < 0)
		return failed("stream on", ret);
	detail = path;
	return 0;
}

void V4l2Stream::onReadable(uint32_t revents)
{
	if (revents & (EPOLLERR | EPOLLHUP))
		return fail(-ENODEV, "device error or disconnected (poll)");
	// At most the ring's worth per wake-up: when converting and handling a
	// frame takes longer than a frame period there is always another buffer,
	// and draining them all would never give the loop back to the other
	// devices, the LEDs and the watchdog (epoll is level-triggered: the rest
	// comes at the next dispatch).
	for (unsigned n = 0; n < kBufferCount; ++n) {
		V4l2Buffer buffer;
		int ret = device_.dequeueBuffer(buffer);
		if (ret == -EAGAIN)
			return;
		if (ret < 0)
			return fail(ret, std::string("dequeue: ") + std::strerror(-ret));
		if (buffer.timestampNs == 0)
			buffer.timestampNs = loop_->nowUs() * 1000u;
		if (buffer.error || onBuffer_(buffer, format_) < 0) {
			status_.droppedFrames++;
		} else {
			stall_.frame(loop_->nowUs());
			if (!delivered_) {
				delivered_ = true;
				backoff_.reset();
				setStatus(DeviceState::Streaming, 0, "");
			}
		}
		if (!open_)
			return; // the frame handler stopped us
		ret = device_.queueBuffer(buffer.index);
		if (ret < 0)
			return fail(ret, std::string("queue buffer: ") + std::strerror(-ret));
	}
}

// Error-flagged or unconvertible buffers do not count as frames either, so a
// device delivering only garbage is re-opened like a silent one.
void V4l2Stream::onWatchdog()
{
	if (open_ && stall_.stalled(loop_->nowUs()))
		fail(-ETIMEDOUT, "no frame for " + std::to_string(config_.timeoutUs / 1000) + " ms");
}

void V4l2Stream::fail(int error, const std::string &detail)
{
	if (!open_)
		return;
	open_ = false;
	io_.reset();
	watchdog_.reset();
	device_.close();
	setStatus(DeviceState::Lost, error, resolveVideoDevice(config_.device) + ": " + detail);
	loop_->addTimer(backoff_.nextDelayUs(), [this] { tryOpen(); }, retryTimer_);
}

} // namespace depthkey
