#include "algo/trimap_union.hpp"

#include "algo/trimap.hpp"

#include <algorithm>

namespace depthkey {

namespace {

// DepthSeeder::evidence's neutral value, and how far from it a frame's
// depth must be to count as sure: only edges both frames are sure of are
// followed (noisy depth disagrees by noise, not by motion; measured: 0, 32,
// 64 and 100 all gain the clean depth camera 0.02 BF, 64 and up cost the
// noisy ones least).
constexpr int kNeither = 128, kSure = 64;

bool saysLecturer(uint8_t evidence) { return evidence > kNeither + kSure; }
bool saysBoard(uint8_t evidence) { return evidence < kNeither - kSure; }
bool disagree(uint8_t a, uint8_t b) { return (saysLecturer(a) && saysBoard(b)) || (saysBoard(a) && saysLecturer(b)); }

} // namespace

void interpolateEdgesInRow(const uint8_t *a, const uint8_t *b, int x0, int x1, int laterQ8, uint8_t *out)
{
	for (int x = x0; x < x1;) {
		if (!disagree(a[x], b[x])) {
			++x;
			continue;
		}
		// A run [start, x) where the two frames disagree: swept by an
		// edge between the two captures.
		const int start = x;
		while (x < x1 && disagree(a[x], b[x]))
			++x;
		const bool lecturerLeft = start > x0 && saysLecturer(a[start - 1]) && saysLecturer(b[start - 1]);
		const bool lecturerRight = x < x1 && saysLecturer(a[x]) && saysLecturer(b[x]);
		if (lecturerLeft == lecturerRight)
			continue; // no edge to follow (all of it moved, or a gap closed): the blend stays
		// The frame that covers the run has its edge at the far end, the
		// other at the near end; at the colour frame's time the edge lies
		// between, laterQ8 / 256 of the way from a's edge to b's.
		const int length = x - start;
		const bool aCovers = saysLecturer(a[start]);
		const int fromA = aCovers ? (length * (256 - laterQ8) + 128) >> 8 : (length * laterQ8 + 128) >> 8;
		// fromA pixels of the run, counted from the lecturer's side, are
		// his at the colour frame's time.
		for (int i = 0; i < length; ++i) {
			const int k = lecturerLeft ? start + i : x - 1 - i;
			out[k] = i < fromA ? std::max(a[k], b[k]) : std::min(a[k], b[k]);
		}
	}
}

void uniteTrimaps(const MappedSeeds &a, const MappedSeeds &b, int laterQ8, MappedSeeds &out)
{
	const int w = a.trimap.width(), h = a.trimap.height();
	Roi &roi = out.roi;
	out.clear(w, h);
	out.lecturerBeyondBorder = a.lecturerBeyondBorder || b.lecturerBeyondBorder;
	if (&a == &b) {
		// One depth frame (no later one yet): the union of it with itself
		// is itself, whatever laterQ8 ((e * (256 - l) + e * l + 128) >> 8 = e,
		// equal labels stay, no edge swept). A copy, not a blend per pixel:
		// at 1080p that loop cost 15 M instructions a frame.
		roi = a.roi;
		for (int y = roi.y0; y < roi.y1; ++y) {
			std::copy(a.trimap.row(y) + roi.x0, a.trimap.row(y) + roi.x1, out.trimap.row(y) + roi.x0);
			std::copy(a.evidence.row(y) + roi.x0, a.evidence.row(y) + roi.x1, out.evidence.row(y) + roi.x0);
		}
		return;
	}
	if (a.roi.empty() || b.roi.empty()) {
		// One side saw no lecturer: he may be where the other saw him (as
		// far as it is in time), and is surely nowhere.
		const MappedSeeds &seen = a.roi.empty() ? b : a;
		const int weight = a.roi.empty() ? laterQ8 : 256 - laterQ8;
		roi = seen.roi;
		for (int y = roi.y0; y < roi.y1; ++y) {
			const uint8_t *s = seen.trimap.row(y);
			uint8_t *o = out.trimap.row(y);
			const uint8_t *se = seen.evidence.row(y);
			uint8_t *oe = out.evidence.row(y);
			for (int x = roi.x0; x < roi.x1; ++x) {
				o[x] = s[x] == kTrimapBoard ? kTrimapBoard
							    : uint8_t(std::clamp((s[x] * weight + 128) >> 8, 1, 254));
				oe[x] = uint8_t((se[x] * weight + 128) >> 8);
			}
		}
		return;
	}
	roi = { std::min(a.roi.x0, b.roi.x0), std::min(a.roi.y0, b.roi.y0), std::max(a.roi.x1, b.roi.x1),
		std::max(a.roi.y1, b.roi.y1) };
	for (int y = roi.y0; y < roi.y1; ++y) {
		const uint8_t *p = a.trimap.row(y), *q = b.trimap.row(y);
		uint8_t *o = out.trimap.row(y);
		const uint8_t *pe = a.evidence.row(y), *qe = b.evidence.row(y);
		uint8_t *oe = out.evidence.row(y);
		for (int x = roi.x0; x < roi.x1; ++x) {
			// The depth evidence blended by time (0 outside a superset:
			// that frame says board).
			oe[x] = uint8_t((pe[x] * (256 - laterQ8) + qe[x] * laterQ8 + 128) >> 8);
			// Equal labels stay; any other pair is undecided (1..254),
			// blended by time. Exact in 16 bits: 255 * 256 + 128 < 2^16.
			const int blend = (p[x] * (256 - laterQ8) + q[x] * laterQ8 + 128) >> 8;
			o[x] = p[x] == q[x] ? p[x] : uint8_t(std::clamp(blend, 1, 254));
		}
		interpolateEdgesInRow(pe, qe, roi.x0, roi.x1, laterQ8, oe);
	}
}

} // namespace depthkey
