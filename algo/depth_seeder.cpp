#include "algo/depth_seeder.hpp"

#include "algo/trimap.hpp"

#include <algorithm>

namespace depthkey {

void DepthSeeder::configure(const SegmentationSettings &segmentation, const LearningSettings &learning)
{
	settings_ = segmentation;
	marginPx_ = learning.marginPx;
}

void DepthSeeder::seed(const DepthFrame &depth, DepthSeeds &out)
{
	const int w = depth.depthMm.width(), h = depth.depthMm.height();
	const size_t n = static_cast<size_t>(w) * h;
	out.labels.resize(w, h);
	out.learnBoard.resize(w, h);
	trusted_.resize(w, h);
	bool amplitudeOk = depth.amplitude.width() == w && depth.amplitude.height() == h;

	const uint16_t *d = depth.depthMm.data();
	const uint16_t *a = amplitudeOk ? depth.amplitude.data() : nullptr;
	const unsigned nearU = unsigned(settings_.nearMm), spanU = unsigned(settings_.farMm - settings_.nearMm);
	const unsigned minA = unsigned(settings_.minAmplitude), spanA = unsigned(settings_.maxAmplitude - settings_.minAmplitude);
	uint8_t *t = trusted_.data();
	for (size_t i = 0; i < n; ++i) {
		// One unsigned compare per interval: near <= d <= far, minA <= a < maxA.
		bool inRange = unsigned(d[i]) - nearU <= spanU;
		bool trusted = a && unsigned(a[i]) - minA < spanA;
		t[i] = inRange && trusted ? 255 : 0;
	}

	erodeSquare(trusted_, settings_.erodePx, subset_, morphology_, path_);
	// Of the in-range areas, the one with the most pixels in front of the
	// static background is the lecturer (a desk in range never is); the
	// largest when nothing has moved yet.
	background_.update(depth.depthMm, moving_);
	out.lecturerPixels = keepPreferredComponent(subset_, moving_, components_);
	dilateSquare(subset_, settings_.dilatePx, superset_, morphology_, path_);
	dilateSquare(subset_, settings_.dilatePx + marginPx_, far_, morphology_, path_);

	uint64_t depthSum = 0;
	const uint8_t *sub = subset_.data(), *sup = superset_.data(), *f = far_.data();
	uint8_t *labels = out.labels.data(), *learn = out.learnBoard.data();
	for (size_t i = 0; i < n; ++i) {
		labels[i] = sub[i] ? kTrimapLecturer : sup[i] ? kTrimapUndecided : kTrimapBoard;
		learn[i] = f[i] ? 0 : 255;
		if (sub[i])
			depthSum += d[i];
	}
	out.lecturerDepthMm = out.lecturerPixels ? int(depthSum / unsigned(out.lecturerPixels)) : 0;
}

} // namespace depthkey
