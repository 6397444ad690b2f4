#include "algo/decaying_histogram.hpp"

#include <algorithm>
#include <cmath>
#include <new>

namespace depthkey {

DecayingHistogram::DecayingHistogram()
	: bins_(static_cast<uint32_t *>(std::calloc(kQuantisedColours, sizeof(uint32_t))))
{
	if (!bins_)
		throw std::bad_alloc(); // as the vector it replaced, once at construction
}

void DecayingHistogram::setRate(double rate)
{
	rate_ = std::clamp(rate, 0.0, 1.0);
	growth_ = rate_ >= 1.0 ? 1.0 : 1.0 / (1.0 - rate_);
}

void DecayingHistogram::clear()
{
	// Every count is in total_ (rescale() keeps it so): none, nothing to zero.
	// Only non-zero bins are written: a page of colours never seen stays
	// the kernel's zero page, not resident memory (see rescale()).
	if (total_ != 0)
		for (uint32_t i = 0; i < kQuantisedColours; ++i)
			if (bins_[i])
				bins_[i] = 0;
	total_ = 0;
	incrementExact_ = kStartIncrement;
	increment_ = kStartIncrement;
}

void DecayingHistogram::endFrame()
{
	if (rate_ >= 1.0) {
		clear(); // only the next frame will count
		return;
	}
	incrementExact_ *= growth_;
	if (incrementExact_ >= kMaxIncrement)
		rescale(8);
	else if (total_ >= kMaxTotal)
		rescale(1);
	increment_ = static_cast<uint32_t>(std::lround(incrementExact_));
}

void DecayingHistogram::rescale(int shift)
{
	// Empty bins are only read: writing them would make every page of the
	// 1 MB resident, where a scene's colours fill only some (issue 15).
	uint64_t total = 0;
	for (uint32_t i = 0; i < kQuantisedColours; ++i)
		if (uint32_t b = bins_[i]) {
			b >>= shift;
			bins_[i] = b;
			total += b;
		}
	total_ = total;
	if (shift == 8)
		incrementExact_ /= 256.0;
}

size_t DecayingHistogram::collect(const QuantisedLab &lab, WeightedLab *out) const
{
	size_t n = 0;
	for (uint32_t i = 0; i < kQuantisedColours; ++i)
		if (bins_[i])
			out[n++] = { lab[i], bins_[i] };
	return n;
}

} // namespace depthkey
