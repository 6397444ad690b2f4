// The band decision's post-processing (SioxRefiner steps 3 and 4), on runs:
//   keepTouchingLecturer: every 4-connected lecturer region of the band that
//     touches a surely-lecturer pixel (or the image border, when the lecturer
//     goes on beyond it) stays, as does one of at least minKeep pixels; the
//     rest becomes board;
//   fillHoles: every board region of the band that reaches no surely-board
//     pixel and not the border is a hole: lecturer, except where the
//     confidence says board clearly.
// Both were floods over pixels (about 100 instructions a band pixel in all,
// 6 M a 640x480 lecture frame and 40 M at 1080p, issue 28). Here a region is
// a set of runs, a row's pixels of one decision between two others, joined
// by union-find where runs of neighbouring rows overlap: the per-pixel work
// is marking a run, reading the rows beside it until its region is anchored,
// and writing the result. The answer is the floods' exactly
// (tests/band_components_test.cpp keeps them as the reference).
//
// The working mask is SioxRefiner's: (w+2) x (h+2) with a frame of
// kBandOutside, seeds 0 (board) or 255 (lecturer), band pixels 0 or 255.
#pragma once

#include "algo/band_graph_cut.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace depthkey {

// The working mask's frame around the image.
constexpr uint8_t kBandOutside = 3;

class BandComponents
{
public:
	// Room for the runs of a band of up to this many pixels: call when the
	// image size changes, so that a steady state allocates nothing.
	void reserve(size_t bandPixels);

	void keepTouchingLecturer(uint8_t *mask, int stride, const std::vector<BandSpan> &spans,
				  bool lecturerBeyondBorder, size_t minKeep);
	// confidence: one per band pixel, in the spans' order.
	void fillHoles(uint8_t *mask, int stride, const std::vector<BandSpan> &spans, const uint8_t *confidence,
		       uint8_t clearlyBoard);

private:
	struct Run {
		int32_t p;      // its first pixel's index in the mask
		int32_t n;      // its length
		int32_t k;      // its first pixel's index in the band arrays
		int32_t y, x0;  // where it is
		int32_t parent; // union-find; a root holds its region's size and anchor
		uint32_t size;
		bool anchored;
	};

	// Collects the band's runs of `value`, marks them `mark` in the mask
	// (so that a neighbour of another value is known to be no band pixel
	// of this decision) and joins the ones that touch.
	void collect(uint8_t *mask, int stride, const std::vector<BandSpan> &spans, uint8_t value, uint8_t mark);
	// Whether any neighbour of the run outside it satisfies `anchor`.
	template<typename Anchor>
	void anchor(const uint8_t *mask, int stride, Anchor isAnchor);
	int32_t find(int32_t r);
	void join(int32_t a, int32_t b);

	std::vector<Run> runs_;
};

} // namespace depthkey
