#include "algo/board_warp_rows.hpp"

#include "algo/composite.hpp"

#include <cstring>

namespace depthkey {

namespace {

inline unsigned lerp8(unsigned a, unsigned b, unsigned f)
{
	return (a * (256u - f) + b * f + 128u) >> 8;
}

} // namespace

void boardWarpRow_C(const BoardWarpRow &r, int opacityQ8)
{
	for (int x = 0; x < r.count; ++x) {
		uint64_t top, bottom;
		if (!loadTaps(r, x, top, bottom))
			continue;
		const int32_t k = r.index[x];
		const unsigned fx = r.frac[x] & 255u, fy = r.frac[x] >> 8;
		const Rgba8 *s = r.source + k;
		const Rgba8 p00 = s[0], p01 = s[1], p10 = s[r.stride], p11 = s[r.stride + 1];
		auto sample = [&](uint8_t Rgba8::*c) {
			return lerp8(lerp8(p00.*c, p10.*c, fy), lerp8(p01.*c, p11.*c, fy), fx);
		};
		const unsigned cr = sample(&Rgba8::r), cg = sample(&Rgba8::g), cb = sample(&Rgba8::b),
			       ca = sample(&Rgba8::a);
		const unsigned w = compositeWeight(opacityQ8, uint8_t(ca)), wb = 256u - w;
		const Rgb8 b = r.board[x];
		r.composite[x] = { uint8_t((b.r * wb + cr * w + 128u) >> 8), uint8_t((b.g * wb + cg * w + 128u) >> 8),
				   uint8_t((b.b * wb + cb * w + 128u) >> 8) };
		r.layer[x] = { uint8_t(cr), uint8_t(cg), uint8_t(cb), uint8_t(ca) };
	}
}

void boardWarpRow(KernelPath path, const BoardWarpRow &row, int opacityQ8)
{
	if (path == KernelPath::Sse2)
		boardWarpRow_SSE2(row, opacityQ8);
	else
		boardWarpRow_C(row, opacityQ8);
}

} // namespace depthkey
