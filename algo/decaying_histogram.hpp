// A histogram of quantised colours whose old samples fade: bounded memory
// (one uint32 per colour cell) however long the daemon runs.
//
// Fading without touching every bin per frame: instead of multiplying all
// bins by (1 - rate) each frame, each new frame's samples weigh 1 / (1 -
// rate) times more than the last frame's, which gives the same proportions.
// When the weights grow large, every bin is divided by 256 at once (every
// ~80 frames at rate 0.1); when the total would overflow (rate 0 keeps
// everything), every bin is halved, which forgets the oldest samples a little.
#pragma once

#include "algo/colour_signature.hpp"
#include "algo/quantised_colour.hpp"

#include <cstdint>
#include <cstdlib>
#include <memory>

namespace depthkey {

class DecayingHistogram
{
public:
	DecayingHistogram();

	// 0 = never forget, 1 = only the current frame counts.
	void setRate(double rate);
	void clear();

	void add(uint32_t quantised)
	{
		bins_[quantised] += increment_;
		total_ += increment_;
	}
	void endFrame();

	uint64_t total() const { return total_; }
	uint32_t bin(uint32_t quantised) const { return bins_[quantised]; }

	// Writes the non-empty bins as weighted Lab points to out (room for
	// kQuantisedColours) and returns how many.
	size_t collect(const QuantisedLab &lab, WeightedLab *out) const;

private:
	void rescale(int shift);

	// calloc'd: fresh pages are zero without being written, so a histogram
	// that sees a few thousand colours (depthkey-siox's) touches only their
	// pages of its 1 MB, and clear() on an empty one writes nothing.
	struct Free {
		void operator()(uint32_t *p) const { std::free(p); }
	};
	std::unique_ptr<uint32_t[], Free> bins_;
	uint64_t total_ = 0;
	double rate_ = 0.0;
	double growth_ = 1.0;    // per frame: 1 / (1 - rate)
	double incrementExact_ = kStartIncrement;
	uint32_t increment_ = kStartIncrement;
	static constexpr uint32_t kStartIncrement = 256;
	static constexpr uint32_t kMaxIncrement = 1u << 16;
	static constexpr uint64_t kMaxTotal = 1ull << 30;
};

} // namespace depthkey
