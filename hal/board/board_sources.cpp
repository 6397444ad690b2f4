#include "hal/board/board_sources.hpp"

#include "hal/board/image_board_source.hpp"
#include "hal/v4l2/v4l2_cameras.hpp"

namespace depthkey {

int ColourBoardSource::start(EventLoop &loop, FrameHandler onFrame, StatusHandler onStatus)
{
	ColourFrame frame;
	frame.rgb.resize(settings_.width, settings_.height);
	uint32_t c = settings_.colour;
	std::fill(frame.rgb.data(), frame.rgb.data() + frame.rgb.size(), Rgb8{ uint8_t(c >> 16), uint8_t(c >> 8), uint8_t(c) });
	frame.timestampNs = loop.nowUs() * 1000u;
	frame.sequence = 1;
	status_ = { DeviceState::Streaming, 0, "" };
	onStatus(status_);
	onFrame(frame);
	return 0;
}

ColourCameraSettings captureStickSettings(const BoardSettings &board)
{
	ColourCameraSettings s;
	s.backend = "v4l2";
	s.device = board.device;
	s.width = board.width;
	s.height = board.height;
	s.fps = board.fps;
	s.pixelFormat = board.pixelFormat;
	s.timeoutMs = board.timeoutMs;
	return s;
}

std::unique_ptr<BoardSource> createBoardSource(const Settings &settings)
{
	const BoardSettings &b = settings.board;
	if (b.backend == "image")
		return std::make_unique<ImageBoardSource>(b);
	if (b.backend == "v4l2")
		return std::make_unique<V4l2ColourCamera>(captureStickSettings(b), "v4l2-board");
	if (b.backend == "sim")
		return std::make_unique<SimBoardSource>(b, settings.sim);
	return std::make_unique<ColourBoardSource>(b);
}

} // namespace depthkey
