#include "algo/board_model.hpp"

#include "algo/board_learn_rows.hpp"
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
	// A row kernel (algo/board_learn_rows.hpp): the teach row's sums, the
	// colour in .predicted.
	const BoardLearnRows rows = boardLearnRows(kernelPath_);
	BoardTeachSums sums;
	for (int y = phase_; y < h; y += kRowStride)
		rows.learn(colour.row(y), trimap.row(y), model_.row(y), w, sums);
	// The gain of the light against the model as it was before this update
	// (the rows learned here have moved a quarter of the way towards it).
	int gains[3];
	for (int k = 0; k < 3; ++k)
		gains[k] = sums.model[k] ? int(std::clamp<uint64_t>((sums.predicted[k] * 256 + sums.model[k] / 2) / sums.model[k],
								     128, 512))
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
	const int m = std::max(1, marginPx);
	// The 9 alpha pixels at -m, 0, +m in x and y, as row kernels
	// (algo/board_learn_rows.hpp): the three rows ORed into near (x from
	// -m to w + m, 0 outside the image, which is ignored as the per-pixel
	// test did), then which pixels are learned, in trimap bytes for the
	// learn row (its sums are not wanted here). Scratch grows only.
	const size_t nearSize = size_t(w) + 2 * size_t(m);
	if (near_.size() < nearSize)
		near_.resize(nearSize);
	if (select_.size() < size_t(w))
		select_.resize(size_t(w));
	uint8_t *near = near_.data() + m, *select = select_.data();
	std::memset(near - m, 0, size_t(m));
	std::memset(near + w, 0, size_t(m));
	const int lo = std::max(0, roi.x0 - m), hi = std::min(w, roi.x1 + m), n = roi.x1 - roi.x0;
	const BoardLearnRows rows = boardLearnRows(kernelPath_);
	BoardTeachSums unused;
	const int first = roi.y0 + ((lastPhase_ - roi.y0 % kRowStride + kRowStride) % kRowStride);
	for (int y = first; y < roi.y1; y += kRowStride) {
		// A row outside the image adds nothing: row y in its place.
		const uint8_t *at = alpha.row(y);
		const uint8_t *above = y - m >= 0 ? alpha.row(y - m) : at, *below = y + m < h ? alpha.row(y + m) : at;
		rows.alphaOr(above + lo, at + lo, below + lo, near + lo, hi - lo);
		rows.decidedSelect(near + roi.x0, trimap.row(y) + roi.x0, m, select + roi.x0, n);
		rows.learn(colour.row(y) + roi.x0, select + roi.x0, model_.row(y) + roi.x0, n, unused);
	}
}

} // namespace depthkey
