#include "algo/board_picture_prior.hpp"

#include "algo/trimap.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>

namespace depthkey {

int BoardPicturePrior::configure(int colourWidth, int colourHeight, const Homography &colourToBoard,
				 const RadialLens &lens, int boardWidth, int boardHeight)
{
	boardOf_.clear();
	if (colourWidth < 1 || colourHeight < 1 || boardWidth < 1 || boardHeight < 1)
		return -EINVAL;
	colourWidth_ = colourWidth;
	colourHeight_ = colourHeight;
	boardWidth_ = boardWidth;
	boardHeight_ = boardHeight;
	fitScale_ = std::max(1, (colourWidth + 320) / 640);
	boardOf_.assign(size_t(colourWidth) * colourHeight, -1);
	sampled_ = RgbImage(colourWidth, colourHeight, Rgb8{ 0, 0, 0 });
	sampledFrom_ = nullptr;
	onDisplay_ = Gray8Image(colourWidth, colourHeight, kTrimapLecturer);
	for (int y = 0; y < colourHeight; ++y)
		for (int x = 0; x < colourWidth; ++x) {
			double ix, iy, u, v;
			if (!lens.undistort(x, y, ix, iy) || !colourToBoard.apply(ix, iy, u, v))
				continue;
			// Nearest board pixel; off the picture = off the display.
			const double ur = std::floor(u + 0.5), vr = std::floor(v + 0.5);
			if (!(ur >= 0 && vr >= 0 && ur < boardWidth && vr < boardHeight))
				continue;
			const size_t k = size_t(y) * colourWidth + x;
			boardOf_[k] = int32_t(vr) * boardWidth + int32_t(ur);
			onDisplay_.data()[k] = kTrimapBoard;
		}
	pictureRowsOf_.assign(size_t(colourHeight), { boardHeight, -1 });
	for (int y = 0; y < colourHeight; ++y)
		for (int x = 0; x < colourWidth; ++x)
			if (const int32_t b = boardOf_[size_t(y) * colourWidth + x]; b >= 0) {
				auto &[first, last] = pictureRowsOf_[size_t(y)];
				first = std::min(first, int(b / boardWidth));
				last = std::max(last, int(b / boardWidth));
			}
	changedFirst_ = 1;
	changedLast_ = 0;
	for (int &g : gainQ8_)
		g = 256;
	return 0;
}

void BoardPicturePrior::pictureRowsChanged(int firstRow, int lastRow)
{
	if (firstRow > lastRow || !sampledFrom_)
		return; // nothing changed, or all is sampled again anyway
	if (changedFirst_ > changedLast_) {
		changedFirst_ = firstRow;
		changedLast_ = lastRow;
	} else {
		changedFirst_ = std::min(changedFirst_, firstRow);
		changedLast_ = std::max(changedLast_, lastRow);
	}
}

void BoardPicturePrior::sampleRow(const RgbImage &picture, int y)
{
	const Rgb8 *board = picture.data();
	const int32_t *b = boardOf_.data() + size_t(y) * colourWidth_;
	Rgb8 *out = sampled_.row(y);
	for (int x = 0; x < colourWidth_; ++x)
		if (b[x] >= 0)
			out[x] = board[b[x]];
}

bool BoardPicturePrior::predict(const RgbImage &picture, const RgbImage &colour, const BoardModel &model)
{
	if (boardOf_.empty() || picture.width() != boardWidth_ || picture.height() != boardHeight_ ||
	    colour.width() != colourWidth_ || colour.height() != colourHeight_ || model.empty())
		return false;
	if (sampledFrom_ != &picture) {
		for (int y = 0; y < colourHeight_; ++y)
			sampleRow(picture, y);
		sampledFrom_ = &picture;
	} else if (changedFirst_ <= changedLast_) {
		for (int y = 0; y < colourHeight_; ++y)
			if (const auto [first, last] = pictureRowsOf_[size_t(y)]; first <= changedLast_ && last >= changedFirst_)
				sampleRow(picture, y);
	}
	changedFirst_ = 1;
	changedLast_ = 0;
	uint64_t colourSum[3] = {}, pictureSum[3] = {};
	size_t fitted = 0;
	const int rowStep = fitRowStep(), columnStep = fitColumnStep();
	for (int y = 0; y < colourHeight_; y += rowStep) {
		const Rgb8 *c = colour.row(y);
		const Rgb8 *sampled = sampled_.row(y);
		const uint8_t *on = onDisplay_.row(y);
		for (int x = 0; x < colourWidth_; x += columnStep) {
			if (on[x] != kTrimapBoard)
				continue;
			const int d = model.distance(x, y, c[x]);
			if (d < 0 || d > kFitDistance)
				continue;
			const Rgb8 p = sampled[x];
			colourSum[0] += c[x].r;
			colourSum[1] += c[x].g;
			colourSum[2] += c[x].b;
			pictureSum[0] += p.r;
			pictureSum[1] += p.g;
			pictureSum[2] += p.b;
			fitted++;
		}
	}
	if (fitted < kMinFitPixels)
		return false;
	// A channel the picture never lights (a pure green board's red) keeps
	// its previous gain: there is nothing to scale there.
	for (int k = 0; k < 3; ++k)
		if (pictureSum[k] >= fitted)
			gainQ8_[k] = int(std::clamp<uint64_t>((colourSum[k] * 256 + pictureSum[k] / 2) / pictureSum[k], 16, 2048));
	return true;
}

} // namespace depthkey
