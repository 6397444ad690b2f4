#include "hal/sim/colour_backdrop.hpp"

#include <cassert>

namespace depthkey::sim {

namespace {

constexpr int kColumns = BoardGeometry::texelColumns();

} // namespace

void ColourBackdrop::build(int width, const std::vector<int32_t> &texelOf, const std::vector<Rgb8> &staticColour)
{
	width_ = width;
	const int height = static_cast<int>(texelOf.size() / width);
	size_t boardPixels = 0;
	for (int32_t t : texelOf)
		boardPixels += t >= 0;
	// Sized once: a vector grown by push_back keeps up to twice its bytes.
	steps_.clear();
	steps_.reserve(boardPixels);
	escapes_.clear();
	rowWords_.assign(width, 0);
	words_.begin(width, height);
	int32_t previous = 0;
	for (int y = 0; y < height; ++y) {
		for (int x = 0; x < width; ++x) {
			const size_t k = static_cast<size_t>(y) * width + x;
			const int32_t texel = texelOf[k];
			if (texel < 0) {
				rowWords_[x] = pack(staticColour[k]);
				continue;
			}
			rowWords_[x] = kBoard;
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
		words_.appendRow(rowWords_.data());
	}
	words_.finish();
	escapes_.shrink_to_fit();
	ticks_.clear();
}

void ColourBackdrop::pick(const std::vector<BoardTexel> &raster)
{
	ticks_.clear(); // keeps its capacity from the cycle before
	// The new words are built beside the old, which say which pixels are on
	// the board and hold the colours off it.
	RowPalette<uint32_t> picked;
	picked.begin(width_, words_.height());
	int32_t texel = 0;
	size_t step = 0, escape = 0;
	for (int y = 0; y < words_.height(); ++y) {
		const uint32_t *old = words_.row(y);
		for (int x = 0; x < width_; ++x) {
			if (!(old[x] & kBoard)) {
				rowWords_[x] = old[x];
				continue;
			}
			const uint8_t s = steps_[step++];
			texel = s == kEscape ? escapes_[escape++]
					     : texel + (s & 15) - 8 + ((s >> 4) - 8) * kColumns;
			const BoardTexel &t = raster[static_cast<size_t>(texel)];
			assert(t.ink <= kInkMask);
			rowWords_[x] = kBoard | uint32_t(t.ink) << kInkShift | pack(t.background);
			if (t.ink)
				ticks_.push_back(t.writeTick | uint32_t(t.eraseTick) << 16);
		}
		picked.appendRow(rowWords_.data());
	}
	picked.finish();
	words_ = std::move(picked);
}

} // namespace depthkey::sim
