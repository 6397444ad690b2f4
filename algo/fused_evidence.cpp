#include "algo/fused_evidence.hpp"

#include <algorithm>

namespace depthkey {

void FusedEvidence::bind(const RgbImage &colour, const Gray8Image &depthEvidence, SioxClassifier &classifier,
			 const BoardModel &board, const Gray8Image *previousAlpha, const RgbImage *previousColour,
			 const Roi &previousRoi)
{
	colour_ = &colour;
	depthEvidence_ = &depthEvidence;
	classifier_ = &classifier;
	board_ = board.empty() ? nullptr : &board;
	previousAlpha_ = previousAlpha;
	previousColour_ = previousColour;
	previousRoi_ = previousAlpha && previousColour ? previousRoi : Roi{};
	if (distance_.size() < size_t(colour.width())) {
		distance_.resize(size_t(colour.width()));
		change_.resize(size_t(colour.width()));
		held_.resize(size_t(colour.width()));
	}
	++frame_;
	const uint16_t old = uint16_t(frame_ - 2 * kStampRefresh);
	if (lastMoved_.size() != colour.size()) {
		lastMoved_.assign(colour.size(), old); // once per size: never moved
		lastInFront_.assign(colour.size(), old);
	} else if (frame_ % kStampRefresh == 0) {
		for (std::vector<uint16_t> *stamps : { &lastMoved_, &lastInFront_ })
			for (uint16_t &stamp : *stamps)
				if (uint16_t(frame_ - stamp) >= kStampRefresh)
					stamp = old;
	}
}

void FusedEvidence::configure(const DecisionSettings &s)
{
	const int match = std::clamp(s.boardMatch, 1, 255);
	// Near how the board looks here: board, by how near. Far from it:
	// something is in front of it (new ink is thin, the lecturer is not), up
	// to half the weight.
	boardSaturates_ = 3 * match;
	boardTerm_[0] = 0;
	for (int d = 0; d <= boardSaturates_; ++d)
		boardTerm_[size_t(d + 1)] =
			int16_t(d < match	   ? -(s.boardWeight * (match - d) / match)
				: d > 2 * match ? s.boardWeight * std::min(d - 2 * match, match) / (2 * match)
						: 0);
	for (int e = 0; e < 256; ++e)
		depthTerm_[size_t(e)] = int16_t((s.depthWeight * (e - s.depthPivot)) >> 6);
	temporalWeight_ = s.temporalWeight;
	depthPivot_ = s.depthPivot;
	stillColour_ = std::max(1, s.stillColour);
	temporalDivisor_.set(uint32_t(128 * stillColour_));
}

void FusedEvidence::confidences(int y, int x0, int x1, uint8_t *out)
{
	const Rgb8 *c = colour_->row(y);
	const uint8_t *e = depthEvidence_->row(y);
	const bool previousRow = y >= previousRoi_.y0 && y < previousRoi_.y1;
	const uint8_t *pa = previousRow ? previousAlpha_->row(y) : nullptr;
	const Rgb8 *pc = previousRow ? previousColour_->row(y) : nullptr;
	// The span with a previous frame, [t0, t1) within [x0, x1): three plain
	// loops instead of a test of the previous ROI at every pixel.
	const int t0 = pa ? std::clamp(previousRoi_.x0, x0, x1) : x1;
	const int t1 = pa ? std::clamp(previousRoi_.x1, t0, x1) : x1;
	// The sums first, by the row kernels; the lookups per pixel after.
	// (Both indexed from x0.)
	int16_t *distance = distance_.data(), *change = change_.data();
	if (board_)
		boardDistance_(c + x0, board_->row(y) + x0, board_->gainQ8(), x1 - x0, distance);
	else
		std::fill(distance, distance + (x1 - x0), int16_t(-1));
	uint8_t *held = held_.data();
	if (t0 < t1) {
		colourChange_(c + t0, pc + t0, t1 - t0, change + (t0 - x0));
		const size_t at = size_t(y) * size_t(colour_->width()) + size_t(t0);
		stillHold_(change + (t0 - x0), e + t0, t1 - t0, { stillColour_, depthPivot_, kHoldFrames, frame_ },
			   lastMoved_.data() + at, lastInFront_.data() + at, held + (t0 - x0));
	}
	auto span = [&]<bool kPrevious>(int from, int to) {
		for (int x = from, k = from - x0; x < to; ++x, ++k) {
			const int siox = classifier_->confidence(quantiseColour(c[x]));
			*out++ = fuse(siox, e[x], distance[k], kPrevious ? pa[x] : -1, kPrevious ? change[k] : 0,
				      kPrevious && held[k]);
		}
	};
	span.template operator()<false>(x0, t0);
	span.template operator()<true>(t0, t1);
	span.template operator()<false>(t1, x1);
}

} // namespace depthkey
