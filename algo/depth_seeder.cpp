#include "algo/depth_seeder.hpp"

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
	const unsigned minA = unsigned(settings_.minAmplitude), spanA = unsigned(settings_.maxAmplitude - settings_.minAmplitude);
	uint8_t *t = trusted_.data();
	for (size_t i = 0; i < n; ++i) {
		// One unsigned compare per interval: near <= d <= far, minA <= a < maxA.
		bool inRange = unsigned(d[i]) - nearU <= spanU;
		bool trusted = a && unsigned(a[i]) - minA < spanA;
		t[i] = inRange && trusted ? 255 : 0;
	}

	// Which in-range area is the lecturer: algo/lecturer_picker.hpp.
	background_.update(depth.depthMm, moving_);
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

	uint64_t depthSum = 0;
	const uint8_t *sub = subset_.data(), *sup = superset_.data();
	uint8_t *labels = out.labels.data();
	for (size_t i = 0; i < n; ++i) {
		labels[i] = sub[i] ? kTrimapLecturer : sup[i] ? kTrimapUndecided : kTrimapBoard;
		if (sub[i])
			depthSum += d[i];
	}
	out.lecturerDepthMm = out.lecturerPixels ? int(depthSum / unsigned(out.lecturerPixels)) : 0;
}

} // namespace depthkey
