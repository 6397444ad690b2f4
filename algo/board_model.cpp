#include "algo/board_model.hpp"

#include "algo/board_teach_rows.hpp"

#include <algorithm>
#include <cstring>

namespace depthkey {

void BoardModel::reset()
{
	if (!model_.empty())
		std::memset(static_cast<void *>(model_.data()), 0, model_.size() * sizeof(Rgba8));
	phase_ = 0;
	teachPhase_ = 0;
}

void BoardModel::learn(const RgbImage &colour, const Gray8Image &trimap)
{
	const int w = colour.width(), h = colour.height();
	if (trimap.width() != w || trimap.height() != h)
		return;
	if (model_.width() != w || model_.height() != h) {
		model_.resize(w, h);
		reset();
	}
	uint64_t colourSum[3] = {}, modelSum[3] = {};
	for (int y = phase_; y < h; y += kRowStride) {
		const Rgb8 *c = colour.row(y);
		const uint8_t *t = trimap.row(y);
		Rgba8 *m = model_.row(y);
		for (int x = 0; x < w; ++x) {
			if (t[x] != kTrimapBoard)
				continue;
			if (m[x].a == 0) {
				m[x] = { c[x].r, c[x].g, c[x].b, 1 };
				continue;
			}
			colourSum[0] += c[x].r;
			colourSum[1] += c[x].g;
			colourSum[2] += c[x].b;
			modelSum[0] += m[x].r;
			modelSum[1] += m[x].g;
			modelSum[2] += m[x].b;
			update(m[x], c[x]);
		}
	}
	// The gain of the light against the model as it was before this update
	// (the rows learned here have moved a quarter of the way towards it).
	int gains[3];
	for (int k = 0; k < 3; ++k)
		gains[k] = modelSum[k] ? int(std::clamp<uint64_t>((colourSum[k] * 256 + modelSum[k] / 2) / modelSum[k], 128, 512))
				       : 256;
	setGains(gains);
	lastPhase_ = phase_;
	phase_ = (phase_ + 1) % kRowStride;
}

void BoardModel::teach(const RgbImage &sampled, const int pictureGainQ8[3], const Gray8Image &mask)
{
	const int w = sampled.width(), h = sampled.height();
	if (model_.width() != w || model_.height() != h || mask.width() != w || mask.height() != h)
		return;
	// Every kTeachRowStride-th row a frame, in turn (a row kernel,
	// algo/board_teach_rows.hpp).
	const BoardTeachRowFn row = boardTeachRow(kernelPath_, pictureGainQ8);
	BoardTeachSums sums;
	for (int y = teachPhase_; y < h; y += kTeachRowStride)
		row(sampled.row(y), mask.row(y), pictureGainQ8, model_.row(y), w, sums);
	teachPhase_ = (teachPhase_ + 1) % kTeachRowStride;
	// The light as the picture predicts it now, against the model before
	// this step: the model follows at a quarter a frame, the gain at once.
	int gains[3] = { gainQ8_[0], gainQ8_[1], gainQ8_[2] };
	for (int k = 0; k < 3; ++k)
		if (sums.model[k])
			gains[k] = int(std::clamp<uint64_t>((sums.predicted[k] * 256 + sums.model[k] / 2) / sums.model[k],
							    128, 512));
	setGains(gains);
}

void BoardModel::setGains(const int gainQ8[3])
{
	if (gainedFilled_ && std::equal(gainQ8, gainQ8 + 3, gainQ8_))
		return;
	for (int k = 0; k < 3; ++k) {
		gainQ8_[k] = gainQ8[k];
		for (int m = 0; m < 256; ++m)
			gained_[k][m] = int16_t((m * gainQ8[k] + 128) >> 8);
	}
	gainedFilled_ = true;
}

void BoardModel::learnDecided(const RgbImage &colour, const Gray8Image &trimap, const Gray8Image &alpha,
			      const Roi &roi, int marginPx)
{
	const int w = colour.width(), h = colour.height();
	if (model_.width() != w || model_.height() != h || alpha.width() != w || alpha.height() != h || roi.empty())
		return;
	marginPx = std::max(1, marginPx);
	auto clearOfLecturer = [&](int x, int y) {
		for (int dy = -marginPx; dy <= marginPx; dy += marginPx) {
			const int yy = y + dy;
			if (yy < 0 || yy >= h)
				continue;
			const uint8_t *a = alpha.row(yy);
			for (int dx = -marginPx; dx <= marginPx; dx += marginPx) {
				const int xx = x + dx;
				if (xx >= 0 && xx < w && a[xx])
					return false;
			}
		}
		return true;
	};
	const int first = roi.y0 + ((lastPhase_ - roi.y0 % kRowStride + kRowStride) % kRowStride);
	for (int y = first; y < roi.y1; y += kRowStride) {
		const Rgb8 *c = colour.row(y);
		const uint8_t *t = trimap.row(y);
		Rgba8 *m = model_.row(y);
		for (int x = roi.x0; x < roi.x1; ++x)
			if (t[x] != kTrimapBoard && t[x] != kTrimapLecturer && clearOfLecturer(x, y))
				update(m[x], c[x]);
	}
}

} // namespace depthkey
