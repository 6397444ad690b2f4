#include "algo/depth_seeder.hpp"

#include "algo/halo_board_depth.hpp"

#include "algo/trimap.hpp"

#include <algorithm>

namespace depthkey {

// Moving pixels in range but outside the chosen lecturer's area.
static int movingOutside(const Gray8Image &trusted, const Gray8Image &chosen, const Gray8Image &moving)
{
	int count = 0;
	for (size_t i = 0; i < trusted.size(); ++i)
		count += trusted.data()[i] && !chosen.data()[i] && moving.data()[i];
	return count;
}

void DepthSeeder::configure(const SegmentationSettings &segmentation)
{
	settings_ = segmentation;
}

void DepthSeeder::seed(const DepthFrame &depth, DepthSeeds &out)
{
	const int w = depth.depthMm.width(), h = depth.depthMm.height();
	const size_t n = static_cast<size_t>(w) * h;
	out.labels.resize(w, h);
	trusted_.resize(w, h);
	bool amplitudeOk = depth.amplitude.width() == w && depth.amplitude.height() == h;

	const uint16_t *d = depth.depthMm.data();
	const uint16_t *a = amplitudeOk ? depth.amplitude.data() : nullptr;
	const unsigned nearU = unsigned(settings_.nearMm), spanU = unsigned(settings_.farMm - settings_.nearMm);
	uint8_t *t = trusted_.data();
	for (size_t i = 0; i < n; ++i) {
		// One unsigned compare per interval: near <= d <= far, minA <= a < maxA.
		bool inRange = unsigned(d[i]) - nearU <= spanU;
		bool trusted = a && trustedEcho(a[i]);
		t[i] = inRange && trusted ? 255 : 0;
	}

	// Which in-range area is the lecturer: algo/lecturer_picker.hpp.
	background_.update(depth.depthMm, moving_);
	// Still furniture in range is no part of him, also where he touches
	// it (algo/furniture_mask.hpp); reach_ is still the last frame's.
	furniture_.update(trusted_, moving_, reach_);
	furniture_.fill(trusted_, 0);
	for (int r = settings_.erodePx; r >= 0; --r) {
		erodeSquare(trusted_, r, subset_, morphology_, path_);
		out.lecturerPixels = picker_.pick(subset_, moving_, components_);
		// The superset grows from the lecturer's whole in-range area (the
		// component holding the subset, before erosion), so an arm
		// thinner than the erosion still lies in the band for SIOX.
		reach_ = trusted_;
		keepComponentsTouching(reach_, subset_, components_);
		// A lecturer only partly in view (an arm reaching in from the
		// edge) is thinner than the erosion: erode less rather than lose
		// him, or keep a still desk while he moves beside it.
		if (out.lecturerPixels > 0 &&
		    (picker_.lastMoved() || movingOutside(trusted_, reach_, moving_) < LecturerPicker::kMinMovingPixels))
			break;
	}
	picker_.remember(subset_);
	dilateSquare(reach_, settings_.dilatePx, superset_, morphology_, path_);
	// The core: deeper inside his in-range area than the subset (an arm
	// thinner than that has none, and is decided by the evidence).
	erodeSquare(reach_, settings_.erodePx + settings_.corePx, core_, morphology_, path_);

	uint64_t depthSum = 0;
	const uint8_t *sub = subset_.data(), *sup = superset_.data(), *core = core_.data(), *in = reach_.data();
	uint8_t *labels = out.labels.data();
	for (size_t i = 0; i < n; ++i) {
		labels[i] = core[i] && sub[i] ? kTrimapLecturer
			    : sub[i]          ? kTrimapSubset
			    : in[i]           ? kTrimapInRange
			    : sup[i]          ? kTrimapUndecided
					      : kTrimapBoard;
		if (sub[i])
			depthSum += d[i];
	}
	out.lecturerDepthMm = out.lecturerPixels ? int(depthSum / unsigned(out.lecturerPixels)) : 0;
	smoothSurface(depth.depthMm, out);
	weighDepth(depth, out);
	// The desk's edge in his band: its depth, in front of him, would read
	// as lecturer; it is furniture, the board's side (1 = surely board).
	furniture_.fill(out.evidence, 1);
	keepCoreWhereDepthIsSure(out);
}

namespace {

// The sum over [x0, x1) x [y0, y1) of an integral image with a zero first
// row and column (stride = width + 1).
uint32_t boxSum(const std::vector<uint32_t> &s, int stride, int x0, int y0, int x1, int y1)
{
	return s[size_t(y1) * stride + x1] - s[size_t(y0) * stride + x1] - s[size_t(y1) * stride + x0] +
	       s[size_t(y0) * stride + x0];
}

} // namespace

void DepthSeeder::keepCoreWhereDepthIsSure(DepthSeeds &out)
{
	// Erosion keeps a gap the lecturer encloses (between the legs, between
	// an arm and his side): the scattered-light halo fills it with depths
	// between his and the board's, in range, and nothing reaches in from
	// outside to erode it. Its pixels' own depth evidence is near neutral
	// there, so the core (which colour cannot overrule) keeps only pixels
	// whose depth is clearly his; the rest are decided on all the evidence.
	uint8_t *labels = out.labels.data();
	const uint8_t *evidence = out.evidence.data();
	for (size_t i = 0; i < out.labels.size(); ++i)
		if (labels[i] == kTrimapLecturer && evidence[i] < kCoreMinEvidence)
			labels[i] = kTrimapSubset;
}

uint8_t DepthSeeder::depthEvidence(int dMm, int amplitude, int intensity, int zLecturerMm, int zBoardMm)
{
	// A learned depth that is not clearly behind him (he stood there for
	// long, or furniture) is no board to compare with.
	const int zB = zBoardMm > zLecturerMm + StaticBackground::kToleranceMm ? zBoardMm
										: zLecturerMm + kUnknownBoardBehindMm;
	// sigma^2 in mm^2: (7500 / sqrt(8) / 2)^2 = 1757813 (rounded: 1758276 =
	// 1326^2, 0.03 % more), times I / A^2; plus the floor's square.
	int64_t variance = int64_t(kNoiseFloorMm) * kNoiseFloorMm;
	variance += amplitude > 0 ? int64_t(1758276) * intensity / (int64_t(amplitude) * amplitude)
				  : int64_t(kNoAmplitudeSigmaMm) * kNoAmplitudeSigmaMm;
	// |zB - zL| < 2^16 and |zL + zB - 2 d| < 2^18 (uint16 depths): times
	// kUnitsPerNat under 2^38, so int64. Truncated towards zero.
	const int64_t units = int64_t(zB - zLecturerMm) * (zLecturerMm + zB - 2 * dMm) * kUnitsPerNat / (2 * variance);
	return uint8_t(std::clamp<int64_t>(128 + units, 1, 254));
}

void DepthSeeder::weighDepth(const DepthFrame &depth, DepthSeeds &out) const
{
	const int w = depth.depthMm.width(), h = depth.depthMm.height();
	out.evidence.resize(w, h);
	const bool haveAmplitude = depth.amplitude.width() == w && depth.amplitude.height() == h &&
				   depth.intensity.width() == w && depth.intensity.height() == h;
	const uint16_t *d = depth.depthMm.data(), *surface = out.surfaceMm.data();
	const uint8_t *labels = out.labels.data();
	uint8_t *evidence = out.evidence.data();
	const int haloPx = settings_.haloPx, stride = w + 1;
	const uint32_t haloArea = uint32_t(2 * haloPx + 1) * uint32_t(2 * haloPx + 1);
	const int shareQ8 = int(settings_.haloShare * 256.0 + 0.5);
	for (size_t i = 0; i < size_t(w) * h; ++i) {
		if (labels[i] == kTrimapBoard) {
			evidence[i] = 0;
			continue;
		}
		const int a = haveAmplitude ? depth.amplitude.data()[i] : 0;
		// No measurement, a weak or a saturated echo: depth says nothing.
		if (d[i] == 0 || (haveAmplitude && !trustedEcho(unsigned(a)))) {
			evidence[i] = 128;
			continue;
		}
		const int zL = surface[i] ? surface[i] : out.lecturerDepthMm;
		int zB = background_.meanMm(i);
		if (haloPx > 0) {
			// The board as the halo lets it read here (algo/halo_board_depth.hpp),
			// from his in-range depths in the box around the pixel.
			const int x = int(i % size_t(w)), y = int(i / size_t(w));
			const int x0 = std::max(0, x - haloPx), x1 = std::min(w, x + haloPx + 1);
			const int y0 = std::max(0, y - haloPx), y1 = std::min(h, y + haloPx + 1);
			const int zBoard = zB > zL + StaticBackground::kToleranceMm ? zB : zL + kUnknownBoardBehindMm;
			zB = haloBoardDepthMm(zBoard, boxSum(depthSums_, stride, x0, y0, x1, y1),
					      boxSum(counts_, stride, x0, y0, x1, y1), haloArea, shareQ8);
		}
		evidence[i] = depthEvidence(d[i], a, haveAmplitude ? depth.intensity.data()[i] : 0, zL, zB);
	}
}

void DepthSeeder::smoothSurface(const Gray16Image &depthMm, DepthSeeds &out)
{
	const int w = depthMm.width(), h = depthMm.height(), stride = w + 1;
	out.surfaceMm.resize(w, h);
	depthSums_.resize(size_t(stride) * (h + 1));
	counts_.resize(depthSums_.size());
	// Integral images of the lecturer's in-range depths and their count
	// (at most 8191 mm x 65536 pixels: fits 32 bits for any ToF camera).
	std::fill(depthSums_.begin(), depthSums_.begin() + stride, 0u);
	std::fill(counts_.begin(), counts_.begin() + stride, 0u);
	for (int y = 0; y < h; ++y) {
		const uint16_t *d = depthMm.row(y);
		const uint8_t *r = reach_.row(y);
		uint32_t rowSum = 0, rowCount = 0;
		uint32_t *sums = depthSums_.data() + size_t(y + 1) * stride, *counts = counts_.data() + size_t(y + 1) * stride;
		sums[0] = counts[0] = 0;
		for (int x = 0; x < w; ++x) {
			rowSum += r[x] ? d[x] : 0;
			rowCount += r[x] ? 1 : 0;
			sums[x + 1] = sums[x + 1 - stride] + rowSum;
			counts[x + 1] = counts[x + 1 - stride] + rowCount;
		}
	}
	const uint16_t fallback = uint16_t(out.lecturerDepthMm);
	const int radius = settings_.surfacePx;
	for (int y = 0; y < h; ++y) {
		const uint8_t *labels = out.labels.row(y);
		uint16_t *surface = out.surfaceMm.row(y);
		const int y0 = std::max(0, y - radius), y1 = std::min(h, y + radius + 1);
		for (int x = 0; x < w; ++x) {
			if (labels[x] == kTrimapBoard) {
				surface[x] = 0;
				continue;
			}
			const int x0 = std::max(0, x - radius), x1 = std::min(w, x + radius + 1);
			const uint32_t count = boxSum(counts_, stride, x0, y0, x1, y1);
			surface[x] = count ? uint16_t((boxSum(depthSums_, stride, x0, y0, x1, y1) + count / 2) / count)
					   : fallback;
		}
	}
}

} // namespace depthkey
