// The daemon's live score (issue 29): every frame it publishes, scored
// against the truth of the time it stands for (ColourFrame::truth, from the
// simulator or a replayed sequence's mask/), as depthkey-eval scores it
// (algo/segmentation_metrics.hpp: IoU and boundary F at 2 px, lecturer
// where >= 128). Reported over the last 5 s of capture time and since the
// start. Pure: the caller gives the times. Allocation-free per frame once
// the frame size is known (the scorer's and the blank layer's buffers are
// reused; the window is a fixed ring).
#pragma once

#include "algo/segmentation_metrics.hpp"

#include <array>
#include <cstdint>

namespace depthkey {

struct LiveScoreFigures {
	uint64_t frames = 0;            // frames scored in the span
	double iou = 0, boundaryF = 0;  // mean per frame; 0 when frames == 0
};

class LiveScore
{
public:
	static constexpr uint64_t kWindowNs = 5'000'000'000ull;

	// A published frame whose lecturer layer (camera geometry) is `lecturer`,
	// standing for capture time captureNs, against that time's truth.
	// Nothing happens without a truth.
	void add(const Gray8Image &lecturer, const Gray8Image &truth, uint64_t captureNs);
	// A frame that went out with no lecturer in it (the board's picture
	// alone): scored as an empty layer.
	void addWithoutLecturer(const Gray8Image &truth, uint64_t captureNs);
	// A frame not published (shed: the box was too slow): the student goes
	// on seeing the last layer that went out, scored against the truth of
	// the time the lost frame stands for. Nothing before a first layer.
	void addRepeated(const Gray8Image &truth, uint64_t captureNs);

	// The frames captured within kWindowNs of the newest scored one.
	LiveScoreFigures recent() const;
	LiveScoreFigures sinceStart() const;
	bool scoring() const { return total_.frames > 0; }
	void reset();

private:
	struct Entry {
		uint64_t captureNs = 0;
		double iou = 0, boundaryF = 0;
	};
	void record(const SegmentationScore &s, uint64_t captureNs);

	SegmentationScorer scorer_{ 2 };
	Gray8Image blank_;
	Gray8Image lastLayer_; // what went out last (a same-size copy a frame)
	// 1024 frames: 5 s at up to 200 fps; at a faster rate the window is shorter.
	std::array<Entry, 1024> ring_{};
	size_t next_ = 0, held_ = 0;
	uint64_t newestNs_ = 0;
	LiveScoreFigures total_;
	double iouSum_ = 0, boundaryFSum_ = 0;
};

} // namespace depthkey
