// Where every frame the daemon makes goes out: today the shared-memory
// streams for the recorder (a FrameSink). A keyed frame and a NO SIGNAL
// frame reach every output through publish(); one more output (a virtual
// webcam) is one more member opened, published to and closed here, and the
// event loop's code does not change. A failed open or publish is logged once
// (DEVICE=shm) and retried with the next frame; the daemon runs on.
#pragma once

#include "algo/capture_slots.hpp"
#include "algo/image.hpp"
#include "hal/frame_sink.hpp"
#include "settings/settings.hpp"

#include <cstdint>
#include <functional>
#include <memory>
#include <string>

namespace depthkey {

// One frame for every output, borrowed for the call.
struct OutputFrame {
	// The composite, in the board's geometry when it is calibrated; null:
	// made from compositeInputs where it goes (FrameSink::publishComposite).
	const RgbImage *composite;
	const CompositeInputs *compositeInputs;
	// The lecturer layer, in the colour camera's geometry, is made from these
	// where it is published (FrameSink::publishLecturer); no colour: NO SIGNAL.
	const RgbImage *colour;
	const Gray8Image &alpha;
	const RgbaImage *boardLecturer;  // the layer in the board's geometry, or null
	uint64_t captureNs;
	uint32_t flags;                  // DK_SHM_FLAG_*
	// Board geometry made where it goes (FrameSink::publishBoard): the
	// composite and the board-geometry layer, in place of composite,
	// compositeInputs and boardLecturer; null: those.
	BoardFrameMaker *boardMaker = nullptr;
};

// The geometry the outputs are opened at.
struct OutputGeometry {
	int width = 0, height = 0;           // the colour camera's
	int boardWidth = 0, boardHeight = 0; // 0 x 0: not in board geometry
};

class FrameOutputs
{
public:
	using SinkFactory = std::function<std::unique_ptr<FrameSink>(const Settings &)>;
	explicit FrameOutputs(SinkFactory makeSink) : makeSink_(std::move(makeSink)) {}

	// Opens (the first time, creates) the outputs; 0 or a negative errno.
	// -EBUSY from the first open, another writer holding an object (a
	// second depthkeyd on the same names), is not logged: the daemon exits
	// with describeError() as its one line rather than run at 0 fps.
	int open(const Settings &settings, const OutputGeometry &geometry);
	// Marks them offline and opens them again, e.g. at a new geometry; a
	// no-op before the first open().
	int reopen(const Settings &settings, const OutputGeometry &geometry);
	// After a reload: re-opens when [output] or the colour size changed. An
	// [output] that cannot be opened (a group we may not chgrp to, a name
	// another user holds) must not cost the recorder its stream: next.output
	// is set back to previous.output, which is opened again. configPath is
	// for the journal.
	void apply(const Settings &previous, Settings &next, const OutputGeometry &geometry,
		   const std::string &configPath);
	void close();
	// A clean stop: the objects are retired and removed (FrameSink::remove).
	void remove();
	// What failed last, naming the object ("" if nothing).
	std::string describeError() const { return sink_ ? sink_->describeError() : std::string(); }

	// Opens again first when the last open failed. The result of the first
	// output that failed, else 0. A keyed frame (with colour) whose capture
	// time skipped slots of the colour camera's interval since the last one
	// is preceded by the last output again for each of them, flagged
	// DK_SHM_FLAG_REPEATED (algo/capture_slots.hpp, issue 29 point 5).
	int publish(const OutputFrame &frame);
	// Capture slots filled with the previous output so far.
	uint64_t repeated() const { return repeated_; }

	// Every 250 ms: samples the readers (logged when their counts change);
	// true when the first came or the last left (the LEDs show that).
	bool sampleReaders(uint64_t nowNs);
	const ReaderCounts &readers() const { return readers_; }
	// Whether a reader was ever counted: "0 readers" is a fault only then
	// (a box with no recorder yet is not one, issue 30).
	bool readerEverAttached() const { return readerEverAttached_; }

private:
	int openSink();
	// ret, or 0 (logged once) for a stream the writer repaired (-EUCLEAN).
	int noteRepair(int ret);
	// The slots between the last keyed frame and this one (publish()).
	void fillSkippedSlots(const OutputFrame &frame);

	SinkFactory makeSink_;
	std::unique_ptr<FrameSink> sink_;
	bool sinkOpen_ = false;
	bool attempted_ = false;    // an open was tried: -EBUSY is no longer the start's
	OutputSettings settings_;   // what open() was given, for the retry in publish()
	OutputGeometry geometry_;
	ReaderCounts readers_;      // recorders reading the shared memory
	bool readerEverAttached_ = false;
	CaptureSlotClock slots_;    // the colour camera's frame slots, keyed frames out
	uint32_t lastKeyedFlags_ = 0;
	uint64_t repeated_ = 0;
};

} // namespace depthkey
