// board.backend "image": a PNG or JPEG file that the board's computer
// replaces, read again when it changes. inotify watches the file's folder
// (a file replaced by rename is a new inode, so watching the file itself
// would lose it): IN_CLOSE_WRITE (written in place and closed) and
// IN_MOVED_TO (renamed over it, the normal case) for its name trigger a
// read through hal/image_file.hpp. A file that cannot be read whole (half
// written, not an image) is refused: Lost with the reader's error, no
// picture delivered, so the daemon keeps the last good one; the next good
// write makes it Streaming again. A missing folder is retried every second.
//
// The file is decoded on a worker thread (hal/background_job.hpp), never on
// the event loop: a 1080p PNG takes tens of milliseconds to decode, and the
// loop hands the keyed frames on (issue 31 point 9: 35 replacements in 10 s
// took the composite from 12 to 3 fps), at nice 10 so that on a busy box
// the keyer's threads come first. Replacements that come while one is
// decoded are read once after it, the newest file then.
#pragma once

#include "hal/background_job.hpp"
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

	// Reads the file now (also what an inotify event does): decoded on the
	// worker, delivered on the loop once decoded.
	void reload();
	uint64_t reads() const { return reads_; }

private:
	void watch();
	void onInotify();
	void onDecoded();
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

	// The worker's: written by the job, read on the loop once it is done.
	RgbImage decoded_;
	int decodeResult_ = 0;
	std::string decodeError_;
	bool reloadAgain_ = false;   // a replacement came while decoding
	uint64_t generation_ = 0;    // a stop() since the job began: its result is not delivered
	BackgroundJob job_;          // last: joined before what its work uses goes
};

} // namespace depthkey
