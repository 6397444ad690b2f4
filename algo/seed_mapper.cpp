#include "algo/seed_mapper.hpp"

#include "algo/max_paint_rows.hpp"

#include <algorithm>
#include <cstdlib>
#include <cstring>

namespace depthkey {


// The footprint of ToF pixel i at depth z: the colour-pixel step to its right
// and lower neighbours at the same depth (the left / upper one on the last
// column / row), rounded up, plus one pixel of overlap. Measured from the
// mapping itself, since a wider ToF lens, lens distortion and parallax make
// one ToF pixel cover more colour pixels than colour size / ToF size.
static void footprintAt(const DepthMapper &mapper, int i, int u, int v, int z, int32_t xQ8, int32_t yQ8,
			int &w, int &h)
{
	const int tw = mapper.tofWidth(), th = mapper.tofHeight();
	int32_t nx, ny, unused;
	mapper.map(u + 1 < tw ? i + 1 : u > 0 ? i - 1 : i, z, nx, unused);
	mapper.map(v + 1 < th ? i + tw : v > 0 ? i - tw : i, z, unused, ny);
	w = (std::abs(nx - xQ8) + 255) / 256 + 1;
	h = (std::abs(ny - yQ8) + 255) / 256 + 1;
}

void SeedMapper::configure(const DepthMapper &mapper)
{
	mapper_ = &mapper;
	// Footprints per ToF pixel and depth bucket, once: two mappings per
	// seed pixel and frame saved.
	const int tw = mapper.tofWidth(), th = mapper.tofHeight(), n = tw * th;
	footprints_.resize(size_t(n) * kFootprintBuckets);
	for (int b = 0; b < kFootprintBuckets; ++b) {
		const int z = kFootprintFirstMm + b * kFootprintStepMm;
		for (int i = 0; i < n; ++i) {
			int32_t x, y;
			mapper.map(i, z, x, y);
			int w, h;
			footprintAt(mapper, i, i % tw, i / tw, z, x, y, w, h);
			footprints_[size_t(b) * n + i] = { uint8_t(std::min(w, 255)), uint8_t(std::min(h, 255)) };
		}
	}
}

const SeedMapper::Footprint &SeedMapper::footprint(int i, int zMm) const
{
	const int bucket = std::clamp((zMm - kFootprintFirstMm + kFootprintStepMm / 2) / kFootprintStepMm, 0,
				      kFootprintBuckets - 1);
	return footprints_[size_t(bucket) * size_t(mapper_->tofWidth() * mapper_->tofHeight()) + size_t(i)];
}

int SeedMapper::colourPixelsPerTofPixel() const
{
	const int tw = mapper_->tofWidth(), th = mapper_->tofHeight();
	if (tw < 2 || th < 2)
		return 1;
	const Footprint &centre = footprint((th / 2) * tw + tw / 2, 1500);
	return std::max(1, std::max<int>(centre.w, centre.h) - 1); // without the one pixel of overlap
}

void MappedSeeds::clear(int width, int height)
{
	if (trimap.width() != width || trimap.height() != height || evidence.width() != width ||
	    evidence.height() != height) {
		trimap.resize(width, height);
		std::memset(trimap.data(), kTrimapBoard, trimap.size());
		evidence.resize(width, height);
		std::memset(evidence.data(), 0, evidence.size());
	} else {
		for (int y = roi.y0; y < roi.y1; ++y) {
			std::memset(trimap.row(y) + roi.x0, kTrimapBoard, size_t(roi.x1 - roi.x0));
			std::memset(evidence.row(y) + roi.x0, 0, size_t(roi.x1 - roi.x0));
		}
	}
	roi = {};
}

void SeedMapper::map(const DepthSeeds &seeds, MappedSeeds &out) const
{
	const int cw = mapper_->colourWidth(), ch = mapper_->colourHeight();
	const int tw = mapper_->tofWidth(), th = mapper_->tofHeight();
	Gray8Image &trimap = out.trimap;
	Roi &roi = out.roi;
	out.clear(cw, ch);

	roi = { cw, ch, 0, 0 };
	out.lecturerBeyondBorder = false;
	bool sizesMatch = seeds.labels.width() == tw && seeds.labels.height() == th &&
			  seeds.surfaceMm.width() == tw && seeds.surfaceMm.height() == th;
	if (!sizesMatch || seeds.lecturerPixels == 0) {
		roi = {};
		return;
	}
	const uint8_t *labels = seeds.labels.data();
	const uint16_t *surface = seeds.surfaceMm.data();
	// Seeds without depth evidence (made by hand, or of another size) are
	// painted as depth saying neither.
	const bool haveEvidence = seeds.evidence.width() == tw && seeds.evidence.height() == th;
	const uint8_t *evidence = haveEvidence ? seeds.evidence.data() : nullptr;
	const MaxPaintFn maxPaint = maxPaintRow(path_);
	for (int i = 0; i < tw * th; ++i) {
		uint8_t label = labels[i];
		if (label == kTrimapBoard)
			continue;
		// The lecturer's smoothed surface (DepthSeeds::surfaceMm).
		int z = surface[i] ? surface[i] : seeds.lecturerDepthMm;
		int32_t xQ8, yQ8;
		mapper_->map(i, z, xQ8, yQ8);
		const Footprint &f = footprint(i, z);
		const int fw = f.w, fh = f.h;
		const int left = (xQ8 - fw * 128 + 128) >> 8, top = (yQ8 - fh * 128 + 128) >> 8; // centred
		int x0 = std::max(0, left), y0 = std::max(0, top);
		int x1 = std::min(cw, left + fw), y1 = std::min(ch, top + fh);
		if (label == kTrimapLecturer && (left < 0 || top < 0 || left + fw > cw || top + fh > ch))
			out.lecturerBeyondBorder = true;
		if (x0 >= x1 || y0 >= y1)
			continue;
		// The depth evidence: where blocks overlap the more lecturer-like
		// wins too (measured: better than the last painted). Lecturer is
		// the highest label: max() with it is a plain store, with no read of
		// what overlapping blocks painted before.
		const uint8_t ev = evidence ? evidence[i] : uint8_t(128);
		const int n = x1 - x0, room = cw - x0;
		for (int y = y0; y < y1; ++y) {
			uint8_t *row = trimap.row(y) + x0;
			maxPaint(out.evidence.row(y) + x0, n, room, ev);
			if (label == kTrimapLecturer)
				std::memset(row, kTrimapLecturer, size_t(n));
			else
				maxPaint(row, n, room, label);
		}
		roi.x0 = std::min(roi.x0, x0);
		roi.y0 = std::min(roi.y0, y0);
		roi.x1 = std::max(roi.x1, x1);
		roi.y1 = std::max(roi.y1, y1);
	}
	if (roi.empty()) {
		roi = {};
	} else {
		// One pixel of board around the painted region, so neighbours of
		// every ROI pixel are inside the ROI or the image border.
		roi = { std::max(0, roi.x0 - 1), std::max(0, roi.y0 - 1), std::min(cw, roi.x1 + 1),
			std::min(ch, roi.y1 + 1) };
	}
}

} // namespace depthkey
