// SSE2 rows of algo/evidence_terms_rows.hpp, four pixels a step: the RGB24
// bytes spread to one 32-bit lane a pixel (rgbToRgbx; each step loads 16
// bytes of which 12 are its own, so it runs while 6 pixels remain, and the
// rest go through the C row). The board model's colour times the gain,
// rounded, is the high half of (m << 8) g plus bit 7 of the low half of
// m g (_mm_mulhi_epu16, _mm_mullo_epi16): (m g + 128) >> 8 exactly, in
// 16-bit lanes. Built without SSE2 (not x86-64) they are the C rows.
#include "algo/evidence_terms_rows.hpp"

#if defined(__SSE2__)
#include "algo/rgb_lanes_sse2.hpp"
#endif

namespace depthkey {

#if defined(__SSE2__)

namespace {

inline __m128i load(const void *p) { return _mm_loadu_si128(static_cast<const __m128i *>(p)); }

// The sum of the three low bytes of each 32-bit lane (the fourth is 0).
inline __m128i sumOfBytes(__m128i v)
{
	const __m128i low = _mm_set1_epi32(0xff);
	return _mm_add_epi32(_mm_and_si128(v, low),
			     _mm_add_epi32(_mm_and_si128(_mm_srli_epi32(v, 8), low), _mm_srli_epi32(v, 16)));
}

// Two pixels' R G B 0 in 16-bit lanes minus the model's gained R G B (its
// fourth lane's gain is 0), as |d|, summed per pixel into 32-bit lanes 0
// and 2.
inline __m128i distancePair(__m128i colour, __m128i model, __m128i gain)
{
	const __m128i one = _mm_set1_epi16(1);
	const __m128i gained = _mm_add_epi16(_mm_mulhi_epu16(_mm_slli_epi16(model, 8), gain),
					     _mm_and_si128(_mm_srli_epi16(_mm_mullo_epi16(model, gain), 7), one));
	const __m128i d = _mm_sub_epi16(colour, gained);
	const __m128i magnitude = _mm_max_epi16(d, _mm_sub_epi16(_mm_setzero_si128(), d));
	const __m128i pairs = _mm_madd_epi16(magnitude, one); // R + G, B + 0 per pixel
	return _mm_add_epi32(pairs, _mm_srli_epi64(pairs, 32));
}

// Four 32-bit values (each fits 16 bits signed) to the low 8 bytes as int16.
inline void store4(int16_t *out, __m128i v)
{
	_mm_storel_epi64(reinterpret_cast<__m128i *>(out), _mm_packs_epi32(v, v));
}

} // namespace

void boardDistanceRow_SSE2(const Rgb8 *colour, const Rgba8 *model, const int gainQ8[3], int n, int16_t *distance)
{
	const __m128i zero = _mm_setzero_si128();
	const __m128i gain = _mm_setr_epi16(short(gainQ8[0]), short(gainQ8[1]), short(gainQ8[2]), 0, short(gainQ8[0]),
					    short(gainQ8[1]), short(gainQ8[2]), 0);
	const __m128i learned = _mm_set1_epi32(kEvidenceLearnedVisits);
	int x = 0;
	for (; x + 6 <= n; x += 4) {
		const __m128i c = rgbToRgbx(load(colour + x)), m = load(model + x);
		const __m128i low = distancePair(_mm_unpacklo_epi8(c, zero), _mm_unpacklo_epi8(m, zero), gain);
		const __m128i high = distancePair(_mm_unpackhi_epi8(c, zero), _mm_unpackhi_epi8(m, zero), gain);
		// Lanes 0 and 2 of each: pixels 0, 1 and 2, 3.
		const __m128i sums = _mm_unpacklo_epi64(_mm_shuffle_epi32(low, _MM_SHUFFLE(3, 3, 2, 0)),
							_mm_shuffle_epi32(high, _MM_SHUFFLE(3, 3, 2, 0)));
		// -1 where the model has too few visits (all bits set).
		const __m128i unlearned = _mm_cmplt_epi32(_mm_srli_epi32(m, 24), learned);
		store4(distance + x, _mm_or_si128(sums, unlearned));
	}
	boardDistanceRow_C(colour + x, model + x, gainQ8, n - x, distance + x);
}

void colourChangeRow_SSE2(const Rgb8 *colour, const Rgb8 *previous, int n, int16_t *change)
{
	int x = 0;
	for (; x + 6 <= n; x += 4) {
		const __m128i c = load(colour + x), p = load(previous + x);
		const __m128i difference = _mm_or_si128(_mm_subs_epu8(c, p), _mm_subs_epu8(p, c));
		store4(change + x, sumOfBytes(rgbToRgbx(difference)));
	}
	colourChangeRow_C(colour + x, previous + x, n - x, change + x);
}

// Eight pixels a step in 16-bit lanes. An age below holdFrames is
// _mm_subs_epu16(holdFrames, age) not 0 (SSE2 has no unsigned compare).
void stillHoldRow_SSE2(const int16_t *change, const uint8_t *evidence, int n, const StillHold &h, uint16_t *moved,
		       uint16_t *inFront, uint8_t *held)
{
	const __m128i zero = _mm_setzero_si128(), one = _mm_set1_epi8(1);
	const __m128i belowStill = _mm_set1_epi16(short(h.still - 1)), pivot = _mm_set1_epi16(short(h.pivot));
	const __m128i frame = _mm_set1_epi16(short(h.frame)), hold = _mm_set1_epi16(short(h.holdFrames));
	auto stamp = [&](__m128i now, uint16_t *stamps) {
		const __m128i s = _mm_or_si128(_mm_and_si128(now, frame), _mm_andnot_si128(now, load(stamps)));
		_mm_storeu_si128(reinterpret_cast<__m128i *>(stamps), s);
		return _mm_cmpeq_epi16(_mm_subs_epu16(hold, _mm_sub_epi16(frame, s)), zero); // age >= holdFrames
	};
	int x = 0;
	for (; x + 8 <= n; x += 8) {
		const __m128i e = _mm_unpacklo_epi8(_mm_loadl_epi64(reinterpret_cast<const __m128i *>(evidence + x)), zero);
		const __m128i movedLong = stamp(_mm_cmpgt_epi16(load(change + x), belowStill), moved + x);
		const __m128i frontLong = stamp(_mm_cmpgt_epi16(e, pivot), inFront + x);
		const __m128i h16 = _mm_andnot_si128(movedLong, frontLong);
		_mm_storel_epi64(reinterpret_cast<__m128i *>(held + x), _mm_and_si128(_mm_packs_epi16(h16, h16), one));
	}
	stillHoldRow_C(change + x, evidence + x, n - x, h, moved + x, inFront + x, held + x);
}

#else

void stillHoldRow_SSE2(const int16_t *change, const uint8_t *evidence, int n, const StillHold &h, uint16_t *moved,
		       uint16_t *inFront, uint8_t *held)
{
	stillHoldRow_C(change, evidence, n, h, moved, inFront, held);
}

void boardDistanceRow_SSE2(const Rgb8 *colour, const Rgba8 *model, const int gainQ8[3], int n, int16_t *distance)
{
	boardDistanceRow_C(colour, model, gainQ8, n, distance);
}

void colourChangeRow_SSE2(const Rgb8 *colour, const Rgb8 *previous, int n, int16_t *change)
{
	colourChangeRow_C(colour, previous, n, change);
}

#endif

} // namespace depthkey
