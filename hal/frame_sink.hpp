// Where the daemon's output frames go: the composite (lecturer over board,
// RGB) and the lecturer alone (RGBA, straight alpha). The real backend is
// shared memory for the recorder (hal/shm_frame_sink.hpp); tests use
// FakeFrameSink (hal/fake_frame_sink.hpp). Publishing never blocks.
#pragma once

#include "algo/board_compositor.hpp"
#include "algo/composite.hpp"
#include "algo/image.hpp"
#include "settings/settings.hpp"

#include <cstdint>
#include <string>

namespace depthkey {

// Readers present on each stream (see ShmRingWriter::countReaders).
struct ReaderCounts {
	int composite = 0;
	int lecturer = 0;
	int boardLecturer = 0; // the board-geometry layer (0 while not calibrated)
	int total() const { return composite + lecturer + boardLecturer; }
	bool operator==(const ReaderCounts &) const = default;
};

// Makes the board geometry's frame where it goes (FrameSink::publishBoard):
// the composite and the board-geometry lecturer layer written straight into
// the streams' next slots, not into images copied there (issue 29 §2).
class BoardFrameMaker
{
public:
	virtual ~BoardFrameMaker() = default;
	// Writes every pixel of target that differs from what target.holds
	// names; returns the tag of what it holds now (BoardCompositor::compose).
	virtual uint64_t make(const BoardTarget &target) = 0;
};

// The usual maker: the compositor's warp of layer (the camera-geometry
// lecturer layer) within roi over board.
struct ComposedBoardFrame : BoardFrameMaker {
	BoardCompositor *compositor = nullptr;
	const RgbaImage *layer = nullptr;
	Roi roi;
	const RgbImage *board = nullptr;
	int opacityQ8 = 256;
	uint64_t make(const BoardTarget &target) override
	{
		return compositor->compose(*layer, roi, *board, opacityQ8, target);
	}
};

class FrameSink
{
public:
	virtual ~FrameSink() = default;

	// Opens the streams at width x height (the colour camera's geometry).
	// With boardWidth > 0 (the board calibrated) the composite is in the
	// board's geometry, boardWidth x boardHeight, and a third stream carries
	// the lecturer layer warped into it. Calling it again (config reload,
	// new resolution or geometry) re-opens them. Returns 0 or a negative errno.
	virtual int open(const OutputSettings &settings, int width, int height, int boardWidth = 0,
			 int boardHeight = 0) = 0;

	// flags: DK_SHM_FLAG_* from hal/depthkey_shm.h. captureNs is the
	// CLOCK_MONOTONIC capture time of the colour frame. Images must have the
	// size given to open() (-EINVAL otherwise); -EBADF when not open.
	virtual int publishComposite(const RgbImage &image, uint64_t captureNs, uint32_t flags) = 0;
	// The same composite made from its parts where it goes (compositeRoiRow(),
	// algo/composite.hpp): no frame-sized image of it kept beside the ring.
	virtual int publishComposite(const CompositeInputs &inputs, uint64_t captureNs, uint32_t flags) = 0;
	// The lecturer layer, made from the colour frame and its alpha
	// (lecturerLayer(), algo/composite.hpp) where it goes, so that no
	// frame-sized RGBA image is kept beside the ring (issue 15). A null
	// colour is the NO SIGNAL frame's layer: transparent black.
	virtual int publishLecturer(const RgbImage *colour, const Gray8Image &alpha, uint64_t captureNs,
				    uint32_t flags) = 0;
	// The board-geometry lecturer layer; -EBADF when opened without a board size.
	virtual int publishBoardLecturer(const RgbaImage &image, uint64_t captureNs, uint32_t flags) = 0;
	// The composite and the board-geometry lecturer layer together, made
	// by maker where they go; -EBADF when opened without a board size. A
	// reader sees both frames whole or not at all: a failure leaves the
	// streams' newest frames as they were.
	virtual int publishBoard(BoardFrameMaker &maker, uint64_t captureNs, uint32_t flags) = 0;

	// Every open stream's newest frame again, stamped captureNs with flags
	// (DK_SHM_FLAG_REPEATED): a capture slot whose frame was shed or keyed
	// late (issue 29 point 5). -ENODATA before a frame was published.
	virtual int repeatLast(uint64_t captureNs, uint32_t flags) = 0;

	// Samples the readers' heartbeats at nowNs (CLOCK_MONOTONIC); called
	// every 250 ms. Never blocks.
	virtual ReaderCounts countReaders(uint64_t nowNs) = 0;

	// Marks the streams offline; consumers keep the last frames.
	virtual void close() = 0;
	// A clean stop: closes and removes what open() created, telling its
	// readers first (docs/shared-memory.md, "When the daemon stops").
	virtual void remove() { close(); }

	// What failed last, naming the object, for the journal; "" if nothing.
	virtual std::string describeError() const = 0;
};

} // namespace depthkey
