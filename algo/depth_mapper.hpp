// The depth -> colour mapping in fixed point. MappingModel (double) says
// where ToF pixel (u, v) at depth z lands:  x2 = S + Tz * z + Tinv / z  (and
// y2 likewise). Everything but z is fixed per ToF pixel, so configure()
// precomputes, per pixel and axis:
//   s    = S * 256                      (Q8 colour pixels)
//   tz   = Tz * 256 * 2^16 / 1000       (Q8 px per mm, 16 extra fraction bits)
//   tinv = Tinv * 1000 * 256            (Q8 px * mm)
// and map() costs four multiplies and no division, in 64-bit integers:
//   x2 (Q8) = s + (tz * zMm) >> 16 + (tinv * r(zMm)) >> 32,
// with r(z) = round(2^32 / z) from a table of every depth (256 KiB, built
// once), since a 64-bit division costs tens of cycles per axis and pixel.
// The reciprocal's rounding adds at most |tinv| / 2^33 Q8 units, far below
// 1/256 px for any real stereo term; the result stays within 1/256 px of the
// model (tests assert the 0.5 px over the whole image and range).
#pragma once

#include "algo/mapping_model.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace depthkey {

class DepthMapper
{
public:
	// Sizes come from the model (colour and ToF resolutions).
	void configure(const MappingModel &model);

	int tofWidth() const { return tofWidth_; }
	int tofHeight() const { return tofHeight_; }
	int colourWidth() const { return colourWidth_; }
	int colourHeight() const { return colourHeight_; }

	// Colour position of ToF pixel index i (v * tofWidth + u) at depth zMm
	// (> 0, at most 65535), in Q8 colour pixels.
	void map(int i, int zMm, int32_t &xQ8, int32_t &yQ8) const
	{
		const Terms &t = terms_[i];
		const int64_t r = kReciprocal[zMm];
		xQ8 = int32_t(t.sx + ((t.tzx * zMm) >> 16) + timesReciprocal(t.tinvx, r));
		yQ8 = int32_t(t.sy + ((t.tzy * zMm) >> 16) + timesReciprocal(t.tinvy, r));
	}

private:
	struct Terms {
		int64_t sx, tzx, tinvx, sy, tzy, tinvy;
	};
	// round(n / z) as (n * round(2^32 / z) + 2^31) >> 32, in 128 bits so
	// that no tinv can overflow.
	static int64_t timesReciprocal(int64_t n, int64_t r)
	{
		return int64_t((static_cast<__int128>(n) * r + (int64_t(1) << 31)) >> 32);
	}

	std::vector<Terms> terms_;
	static const std::array<uint32_t, 65536> kReciprocal; // round(2^32 / z) (z = 1: 2^32 - 1)
	int tofWidth_ = 0, tofHeight_ = 0, colourWidth_ = 0, colourHeight_ = 0;
};

} // namespace depthkey
