// What the SSE2 and SSSE3 rows of algo/board_teach_rows.hpp share: four
// pixels a step, once the prediction is in a register as RGBA bytes (alpha
// 0). The rows differ only in how they get there (SSSE3: one shuffle and one
// rounding multiply a channel; SSE2: shifts and two multiplies).
// SSE2 only, so that both rows inline it.
#pragma once

#include "algo/board_model.hpp"
#include "algo/board_teach_rows.hpp"
#include "algo/trimap.hpp"

#include <cstring>
#include <emmintrin.h>

namespace depthkey::teach_x86 {

static_assert(BoardModel::kRateShift == 2, "the rows' update step is a quarter");
static_assert(sizeof(Rgba8) == 4 && sizeof(Rgb8) == 3, "pixels are packed bytes");

// Per-channel sums in 16-bit lanes [r g b 0 r g b 0], each step adding at
// most 2 * 255 a lane: flushed to 32 bits every kFlushSteps steps, to the
// caller's 64-bit sums at the row's end.
struct Sums {
	static constexpr int kFlushSteps = 64;
	__m128i predicted16 = _mm_setzero_si128(), model16 = _mm_setzero_si128();
	__m128i predicted32 = _mm_setzero_si128(), model32 = _mm_setzero_si128();
	int steps = 0;

	static __m128i widen(__m128i v16)
	{
		const __m128i zero = _mm_setzero_si128();
		return _mm_add_epi32(_mm_unpacklo_epi16(v16, zero), _mm_unpackhi_epi16(v16, zero));
	}
	void flush()
	{
		predicted32 = _mm_add_epi32(predicted32, widen(predicted16));
		model32 = _mm_add_epi32(model32, widen(model16));
		predicted16 = model16 = _mm_setzero_si128();
		steps = 0;
	}
	void add(__m128i predicted8, __m128i model8)
	{
		const __m128i zero = _mm_setzero_si128();
		predicted16 = _mm_add_epi16(predicted16, _mm_add_epi16(_mm_unpacklo_epi8(predicted8, zero),
								       _mm_unpackhi_epi8(predicted8, zero)));
		model16 = _mm_add_epi16(model16,
					_mm_add_epi16(_mm_unpacklo_epi8(model8, zero), _mm_unpackhi_epi8(model8, zero)));
		if (++steps == kFlushSteps)
			flush();
	}
	void into(BoardTeachSums &sums)
	{
		flush();
		uint32_t p[4], m[4];
		_mm_storeu_si128(reinterpret_cast<__m128i *>(p), predicted32);
		_mm_storeu_si128(reinterpret_cast<__m128i *>(m), model32);
		for (int k = 0; k < 3; ++k) {
			sums.predicted[k] += p[k];
			sums.model[k] += m[k];
		}
	}
};

// Four model pixels taught their predictions (RGBA, alpha 0) where mask is
// kTrimapBoard, as boardTeachRow_C does each.
inline void teachFour(__m128i predicted8, const uint8_t *mask, Rgba8 *model, Sums &sums)
{
	const __m128i zero = _mm_setzero_si128();
	const __m128i alphaMask = _mm_set1_epi32(int(0xff000000u)), rgbMask = _mm_set1_epi32(0x00ffffff);
	const __m128i alphaOne = _mm_set1_epi32(0x01000000);
	const __m128i m8 = _mm_loadu_si128(reinterpret_cast<const __m128i *>(model));
	int32_t maskBytes;
	std::memcpy(&maskBytes, mask, 4);
	// Each mask byte spread over its pixel's four bytes, then 0xffffffff
	// where it is board.
	__m128i board = _mm_cvtsi32_si128(maskBytes);
	board = _mm_unpacklo_epi8(board, board);
	board = _mm_unpacklo_epi16(board, board);
	board = _mm_cmpeq_epi8(board, _mm_set1_epi8(char(kTrimapBoard)));
	const __m128i unseen = _mm_cmpeq_epi32(_mm_and_si128(m8, alphaMask), zero);
	const __m128i summed = _mm_andnot_si128(unseen, board);
	sums.add(_mm_and_si128(predicted8, summed), _mm_and_si128(m8, _mm_and_si128(summed, rgbMask)));
	// mean + ((p - mean + 2) >> 2) in signed 16-bit lanes (-253..257 fits).
	const __m128i two = _mm_set1_epi16(2);
	auto step = [&](__m128i p16, __m128i mean16) {
		return _mm_add_epi16(mean16, _mm_srai_epi16(_mm_add_epi16(_mm_sub_epi16(p16, mean16), two), 2));
	};
	const __m128i stepped = _mm_packus_epi16(
		step(_mm_unpacklo_epi8(predicted8, zero), _mm_unpacklo_epi8(m8, zero)),
		step(_mm_unpackhi_epi8(predicted8, zero), _mm_unpackhi_epi8(m8, zero)));
	const __m128i updated = _mm_or_si128(_mm_and_si128(stepped, rgbMask),
					     _mm_and_si128(_mm_adds_epu8(m8, alphaOne), alphaMask));
	const __m128i fresh = _mm_or_si128(predicted8, alphaOne);
	const __m128i taught = _mm_or_si128(_mm_and_si128(unseen, fresh), _mm_andnot_si128(unseen, updated));
	const __m128i out = _mm_or_si128(_mm_and_si128(board, taught), _mm_andnot_si128(board, m8));
	_mm_storeu_si128(reinterpret_cast<__m128i *>(model), out);
}

} // namespace depthkey::teach_x86
