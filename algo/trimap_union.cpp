#include "algo/trimap_union.hpp"

#include "algo/trimap.hpp"

#include <algorithm>
#include <cstring>

namespace depthkey {

void uniteTrimaps(const MappedSeeds &a, const MappedSeeds &b, MappedSeeds &out)
{
	const int w = a.trimap.width(), h = a.trimap.height();
	Roi &roi = out.roi;
	if (out.trimap.width() != w || out.trimap.height() != h) {
		out.trimap.resize(w, h);
		std::memset(out.trimap.data(), kTrimapBoard, out.trimap.size());
		roi = {};
	}
	for (int y = roi.y0; y < roi.y1; ++y)
		std::memset(out.trimap.row(y) + roi.x0, kTrimapBoard, size_t(roi.x1 - roi.x0));
	out.lecturerBeyondBorder = a.lecturerBeyondBorder || b.lecturerBeyondBorder;
	if (a.roi.empty() || b.roi.empty()) {
		// One side saw no lecturer: he may be where the other saw him, and
		// is surely nowhere.
		const MappedSeeds &seen = a.roi.empty() ? b : a;
		roi = seen.roi;
		for (int y = roi.y0; y < roi.y1; ++y) {
			const uint8_t *s = seen.trimap.row(y);
			uint8_t *o = out.trimap.row(y);
			for (int x = roi.x0; x < roi.x1; ++x)
				o[x] = s[x] == kTrimapBoard ? kTrimapBoard : kTrimapUndecided;
		}
		return;
	}
	roi = { std::min(a.roi.x0, b.roi.x0), std::min(a.roi.y0, b.roi.y0), std::max(a.roi.x1, b.roi.x1),
		std::max(a.roi.y1, b.roi.y1) };
	for (int y = roi.y0; y < roi.y1; ++y) {
		const uint8_t *p = a.trimap.row(y), *q = b.trimap.row(y);
		uint8_t *o = out.trimap.row(y);
		for (int x = roi.x0; x < roi.x1; ++x) {
			// Labels are 0, 128, 255: equal labels stay, any other pair is
			// undecided.
			o[x] = p[x] == q[x] ? p[x] : kTrimapUndecided;
		}
	}
}

} // namespace depthkey
