#include "algo/lecturer_picker.hpp"

#include <algorithm>
#include <cstring>

namespace depthkey {

int LecturerPicker::pick(Gray8Image &mask, const Gray8Image &moving, ComponentScratch &scratch)
{
	const int count = labelComponents(mask, scratch);
	const int w = mask.width(), h = mask.height(), stride = w + 2;
	const bool history = everChosen_ && previous_.width() == w && previous_.height() == h;
	const bool motion = moving.width() == w && moving.height() == h;
	// counts[2k] = moving pixels of component k, counts[2k + 1] = overlap.
	scratch.counts.assign(size_t(2) * count, 0);
	for (int y = 0; y < h; ++y) {
		const int32_t *l = scratch.labels.data() + size_t(y + 1) * stride + 1;
		const uint8_t *m = motion ? moving.row(y) : nullptr;
		const uint8_t *p = history ? previous_.row(y) : nullptr;
		for (int x = 0; x < w; ++x) {
			if (l[x] < 0)
				continue;
			int32_t *c = scratch.counts.data() + 2 * l[x];
			c[0] += m && m[x];
			c[1] += p && p[x];
		}
	}
	auto moves = [&](int k) {
		return scratch.counts[size_t(2) * k] >=
		       std::max(kMinMovingPixels, scratch.sizes[size_t(k)] / kMovingShareDivisor);
	};
	bool anyMoves = false;
	for (int k = 0; k < count && !anyMoves; ++k)
		anyMoves = moves(k);
	int best = -1;
	long bestScore = -1;
	for (int k = 0; k < count; ++k) {
		const int size = scratch.sizes[size_t(k)];
		const int movingPixels = scratch.counts[size_t(2) * k], overlap = scratch.counts[size_t(2) * k + 1];
		long score;
		if (!everChosen_) {
			score = size; // no history yet: the biggest
		} else if (confirmed_ || !anyMoves) {
			if (!moves(k) && overlap == 0)
				continue;
			score = 2L * movingPixels + overlap;
		} else {
			// Following a start-up guess that never moved: whatever moves
			// now is the lecturer.
			if (!moves(k))
				continue;
			score = movingPixels;
		}
		if (score > bestScore) {
			bestScore = score;
			best = k;
		}
	}
	lastChosen_ = best >= 0;
	lastMoved_ = lastChosen_ && moves(best);
	keepComponent(mask, scratch, best);
	return best >= 0 ? scratch.sizes[size_t(best)] : 0;
}

void LecturerPicker::remember(const Gray8Image &subset)
{
	const bool chosen = lastChosen_;
	confirmed_ = confirmed_ || lastMoved_; // once the one followed moves
	everChosen_ = everChosen_ || chosen;
	// A frame without him (too thin after erosion, hidden for a moment)
	// keeps where he was last seen: a lecturer standing still, whom the
	// background model has taken in, is found there again. Where he left
	// the view, nothing in range overlaps it.
	if (chosen || previous_.width() != subset.width() || previous_.height() != subset.height()) {
		previous_.resize(subset.width(), subset.height());
		std::memcpy(previous_.data(), subset.data(), subset.size());
	}
}

void LecturerPicker::reset()
{
	everChosen_ = confirmed_ = lastChosen_ = lastMoved_ = false;
}

} // namespace depthkey
