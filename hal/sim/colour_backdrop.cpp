#include "hal/sim/colour_backdrop.hpp"

#include <cassert>

namespace depthkey::sim {

namespace {

constexpr int kColumns = BoardGeometry::texelColumns();

} // namespace

void ColourBackdrop::build(const std::vector<int32_t> &texelOf, const std::vector<Rgb8> &staticColour)
{
	words_.assign(texelOf.size(), 0);
	size_t boardPixels = 0;
	for (int32_t t : texelOf)
		boardPixels += t >= 0;
	// Sized once: a vector grown by push_back keeps up to twice its bytes.
	steps_.clear();
	steps_.reserve(boardPixels);
	escapes_.clear();
	int32_t previous = 0;
	for (size_t k = 0; k < texelOf.size(); ++k) {
		const int32_t texel = texelOf[k];
		if (texel < 0) {
			words_[k] = pack(staticColour[k]);
			continue;
		}
		words_[k] = kBoard;
		const int row = texel / kColumns - previous / kColumns;
		const int column = texel % kColumns - previous % kColumns;
		if (row >= -7 && row <= 7 && column >= -7 && column <= 7) {
			steps_.push_back(static_cast<uint8_t>((column + 8) | (row + 8) << 4));
		} else {
			steps_.push_back(kEscape);
			escapes_.push_back(texel);
		}
		previous = texel;
	}
	escapes_.shrink_to_fit();
	ticks_.clear();
}

void ColourBackdrop::pick(const std::vector<BoardTexel> &raster)
{
	ticks_.clear(); // keeps its capacity from the cycle before
	int32_t texel = 0;
	size_t step = 0, escape = 0;
	for (size_t k = 0; k < words_.size(); ++k) {
		if (!(words_[k] & kBoard))
			continue;
		const uint8_t s = steps_[step++];
		texel = s == kEscape ? escapes_[escape++]
				     : texel + (s & 15) - 8 + ((s >> 4) - 8) * kColumns;
		const BoardTexel &t = raster[static_cast<size_t>(texel)];
		assert(t.ink <= kInkMask);
		words_[k] = kBoard | uint32_t(t.ink) << kInkShift | pack(t.background);
		if (t.ink)
			ticks_.push_back(t.writeTick | uint32_t(t.eraseTick) << 16);
	}
}

} // namespace depthkey::sim
