#include "hal/sim/static_depth.hpp"

#include <algorithm>
#include <bit>

namespace depthkey::sim {

void StaticDepth::assign(int width, int height, const std::vector<float> &z)
{
	width_ = width;
	rows_.assign(height, Row{});
	values_.clear();
	indices_.clear();
	decoded_.assign(width, 0.0f);
	decodedRow_ = -1;
	std::vector<uint32_t> palette;
	for (int j = 0; j < height; ++j) {
		const float *in = z.data() + static_cast<size_t>(j) * width;
		palette.clear();
		for (int i = 0; i < width; ++i)
			palette.push_back(std::bit_cast<uint32_t>(in[i]));
		std::sort(palette.begin(), palette.end());
		palette.erase(std::unique(palette.begin(), palette.end()), palette.end());
		Row &row = rows_[j];
		row.values = static_cast<uint32_t>(values_.size());
		row.whole = palette.size() > 256;
		if (row.whole) {
			values_.insert(values_.end(), in, in + width);
			continue;
		}
		for (uint32_t bits : palette)
			values_.push_back(std::bit_cast<float>(bits));
		row.indices = static_cast<uint32_t>(indices_.size());
		for (int i = 0; i < width; ++i) {
			auto at = std::lower_bound(palette.begin(), palette.end(), std::bit_cast<uint32_t>(in[i]));
			indices_.push_back(static_cast<uint8_t>(at - palette.begin()));
		}
	}
	values_.shrink_to_fit();
	indices_.shrink_to_fit();
}

const float *StaticDepth::row(int j) const
{
	const Row &row = rows_[j];
	if (row.whole)
		return values_.data() + row.values;
	if (j != decodedRow_) {
		const float *palette = values_.data() + row.values;
		const uint8_t *index = indices_.data() + row.indices;
		for (int i = 0; i < width_; ++i)
			decoded_[i] = palette[index[i]];
		decodedRow_ = j;
	}
	return decoded_.data();
}

} // namespace depthkey::sim
