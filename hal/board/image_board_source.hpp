// board.backend "image": a PNG or JPEG file that the board's computer
// replaces, read again when it changes. inotify watches the file's folder
// (a file replaced by rename is a new inode, so watching the file itself
// would lose it): IN_CLOSE_WRITE (written in place and closed) and
// IN_MOVED_TO (renamed over it, the normal case) for its name trigger a
// read through hal/image_file.hpp. A file that cannot be read whole (half
// written, not an image) is refused: Lost with the reader's error, no
// picture delivered, so the daemon keeps the last good one; the next good
// write makes it Streaming again. A missing folder is retried every second.
#pragma once

#include "hal/camera.hpp"
#include "hal/unique_fd.hpp"
#include "settings/settings.hpp"

namespace depthkey {

class ImageBoardSource : public ColourCamera
{
public:
	explicit ImageBoardSource(const BoardSettings &settings) : path_(settings.image) {}
	~ImageBoardSource() override { stop(); }
	std::string name() const override { return "board-image"; }
	int start(EventLoop &loop, FrameHandler onFrame, StatusHandler onStatus) override;
	void stop() override;
	DeviceStatus status() const override { return status_; }

	// Reads the file now (also what an inotify event does).
	void reload();
	uint64_t reads() const { return reads_; }

private:
	void watch();
	void onInotify();
	void setStatus(DeviceState state, int error, const std::string &detail);

	std::string path_, folder_, fileName_;
	EventLoop *loop_ = nullptr;
	FrameHandler onFrame_;
	StatusHandler onStatus_;
	DeviceStatus status_;
	ColourFrame frame_;
	UniqueFd inotify_;
	EventSource io_, retry_;
	uint64_t reads_ = 0;
};

} // namespace depthkey
