#include "hal/board/image_board_source.hpp"

#include "hal/image_file.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <sys/epoll.h>
#include <sys/inotify.h>
#include <sys/resource.h>
#include <unistd.h>
#include <utility>

namespace depthkey {

namespace {

constexpr uint64_t kWatchRetryUs = 1'000'000;
// The decoding thread's nice value (Linux's is per thread): a new picture
// may come a frame or two later, the keyed frames should not. Weight 110
// against the keyer's 1024, as the preview server's threads.
constexpr int kDecodeNice = 10;

// OpenCV's imread decodes a JPEG that was cut short (the board's computer
// died while writing it in place) with only a warning, the rest grey; a
// PNG cut short it refuses. A JPEG ends with the EOI marker FF D9 (encoders
// may pad after it), so one without it near its end is refused here.
// Returns "" or why the file is not whole.
std::string jpegCutShort(const std::string &path)
{
	FILE *f = std::fopen(path.c_str(), "rb");
	if (!f)
		return ""; // the reader says why
	unsigned char head[2] = { 0, 0 }, tail[32];
	size_t n = 0;
	bool jpeg = std::fread(head, 1, 2, f) == 2 && head[0] == 0xFF && head[1] == 0xD8;
	if (jpeg && std::fseek(f, -long(sizeof(tail)), SEEK_END) != 0)
		std::fseek(f, 2, SEEK_SET);
	if (jpeg)
		n = std::fread(tail, 1, sizeof(tail), f);
	std::fclose(f);
	if (!jpeg)
		return "";
	for (size_t i = 0; i + 1 < n; ++i)
		if (tail[i] == 0xFF && tail[i + 1] == 0xD9)
			return "";
	return path + ": a JPEG without its end marker: cut short (half written?)";
}

} // namespace

int ImageBoardSource::start(EventLoop &loop, FrameHandler onFrame, StatusHandler onStatus)
{
	if (path_.empty() || path_[0] != '/')
		return -EINVAL;
	stop();
	loop_ = &loop;
	onFrame_ = std::move(onFrame);
	onStatus_ = std::move(onStatus);
	size_t slash = path_.rfind('/');
	folder_ = slash == 0 ? "/" : path_.substr(0, slash);
	fileName_ = path_.substr(slash + 1);
	frame_.sequence = 0;
	watch();
	return 0;
}

void ImageBoardSource::stop()
{
	generation_++;
	reloadAgain_ = false;
	io_.reset();
	retry_.reset();
	inotify_.reset();
	status_ = { DeviceState::Stopped, 0, "", status_.droppedFrames };
}

void ImageBoardSource::setStatus(DeviceState state, int error, const std::string &detail)
{
	if (status_.set(state, error, detail) && onStatus_)
		onStatus_(status_);
}

// Watch first, then read: a replacement landing in between is not missed.
void ImageBoardSource::watch()
{
	if (!inotify_.isValid())
		inotify_.reset(inotify_init1(IN_NONBLOCK | IN_CLOEXEC));
	int ret = inotify_.isValid() ? 0 : -errno;
	if (ret == 0 && inotify_add_watch(inotify_.get(), folder_.c_str(),
					  IN_CLOSE_WRITE | IN_MOVED_TO | IN_DELETE_SELF | IN_MOVE_SELF | IN_ONLYDIR) < 0)
		ret = -errno;
	if (ret < 0) {
		setStatus(DeviceState::Lost, ret, folder_ + ": cannot watch for a new board picture: " + std::strerror(-ret));
		loop_->addTimer(kWatchRetryUs, [this] { watch(); }, retry_);
		return;
	}
	loop_->addIo(inotify_.get(), EPOLLIN, [this](uint32_t) { onInotify(); }, io_);
	reload();
}

void ImageBoardSource::onInotify()
{
	alignas(struct inotify_event) char buf[4096];
	bool changed = false, folderGone = false;
	for (;;) {
		ssize_t n = ::read(inotify_.get(), buf, sizeof(buf));
		if (n <= 0)
			break;
		for (char *p = buf; p < buf + n;) {
			auto *event = reinterpret_cast<struct inotify_event *>(p);
			if (event->mask & (IN_DELETE_SELF | IN_MOVE_SELF | IN_IGNORED))
				folderGone = true;
			else if (event->len && fileName_ == event->name)
				changed = true;
			p += sizeof(struct inotify_event) + event->len;
		}
	}
	if (folderGone) {
		io_.reset();
		inotify_.reset();
		setStatus(DeviceState::Lost, -ENOENT, folder_ + ": folder gone, watching for it again");
		loop_->addTimer(kWatchRetryUs, [this] { watch(); }, retry_);
		return;
	}
	if (changed)
		reload();
}

void ImageBoardSource::reload()
{
	if (job_.running()) {
		reloadAgain_ = true;
		return;
	}
	reads_++;
	const uint64_t generation = generation_;
	int ret = job_.start(
		*loop_,
		[this, path = path_] {
			// Not allowed to: it decodes at the daemon's priority.
			(void)setpriority(PRIO_PROCESS, static_cast<id_t>(gettid()), kDecodeNice);
			decodeError_ = jpegCutShort(path);
			decodeResult_ = decodeError_.empty() ? readRgbImage(path, decoded_, decodeError_) : -EINVAL;
		},
		[this, generation] {
			if (generation == generation_)
				onDecoded();
			if (std::exchange(reloadAgain_, false))
				reload(); // the newest file, once
		});
	if (ret < 0) {
		status_.droppedFrames++;
		setStatus(DeviceState::Lost, ret,
			  "cannot start reading the board picture, keeping the last good one: " + std::string(std::strerror(-ret)));
	}
}

void ImageBoardSource::onDecoded()
{
	if (decodeResult_ < 0) {
		status_.droppedFrames++;
		setStatus(DeviceState::Lost, decodeResult_,
			  "board picture refused, keeping the last good one: " + decodeError_);
	} else {
		// The frame handed on is the source's own (the daemon may hold it
		// until between frames): swapped in here, on the loop, and the
		// previous pixels reused by the next decode.
		std::swap(frame_.rgb, decoded_);
		frame_.timestampNs = loop_->nowUs() * 1000u;
		frame_.sequence++;
		setStatus(DeviceState::Streaming, 0, "");
		onFrame_(frame_);
	}
}

} // namespace depthkey
