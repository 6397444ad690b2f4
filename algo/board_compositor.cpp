#include "algo/board_compositor.hpp"

#include "algo/board_warp_rows.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace depthkey {

bool BoardCompositor::configure(const Homography &colourToOutput, int colourWidth, int colourHeight,
				int outputWidth, int outputHeight, const RadialLens &lens)
{
	clear();
	Homography outputToColour;
	if (colourWidth < 2 || colourHeight < 2 || outputWidth <= 0 || outputHeight <= 0 ||
	    !colourToOutput.inverse(outputToColour))
		return false;
	colourToOutput_ = colourToOutput;
	lens_ = lens;
	colourWidth_ = colourWidth;
	colourHeight_ = colourHeight;
	const size_t n = size_t(outputWidth) * outputHeight;
	index_.resize(n);
	frac_.resize(n);
	// Seen: within the colour image's pixel area [-0.5, w - 0.5]. The
	// sample point is clamped so that x0 + 1 and y0 + 1 stay inside (at most
	// 1/256 px off at the last row and column), so the kernel needs no
	// bounds checks.
	const long maxX = (colourWidth - 1) * 256L - 1, maxY = (colourHeight - 1) * 256L - 1;
	for (int y = 0; y < outputHeight; ++y)
		for (int x = 0; x < outputWidth; ++x) {
			size_t k = size_t(y) * outputWidth + x;
			double ix, iy, sx = -1, sy = -1;
			bool seen = outputToColour.apply(x, y, ix, iy) && lens.distort(ix, iy, sx, sy) &&
				    std::isfinite(sx) && std::isfinite(sy) && sx >= -0.5 && sx <= colourWidth - 0.5 &&
				    sy >= -0.5 && sy <= colourHeight - 0.5;
			if (!seen) {
				index_[k] = kOutsideView;
				frac_[k] = 0;
				continue;
			}
			long qx = std::clamp(std::lround(sx * 256.0), 0L, maxX), qy = std::clamp(std::lround(sy * 256.0), 0L, maxY);
			index_[k] = int32_t((qy >> 8) * colourWidth + (qx >> 8));
			frac_[k] = uint16_t((qx & 255) | (qy & 255) << 8);
		}
	outputWidth_ = outputWidth;
	outputHeight_ = outputHeight;
	tileSources();
	return true;
}

// Which colour tiles each board tile's pixels read (their 2x2 taps).
void BoardCompositor::tileSources()
{
	tilesX_ = (outputWidth_ + kBoardTile - 1) / kBoardTile;
	tilesY_ = (outputHeight_ + kBoardTile - 1) / kBoardTile;
	colourTilesX_ = (colourWidth_ + kColourTile - 1) / kColourTile;
	colourTilesY_ = (colourHeight_ + kColourTile - 1) / kColourTile;
	tileSources_.assign(size_t(tilesX_) * tilesY_, TileSources{ 0xFFFF, 0xFFFF, 0, 0 });
	occupied_.assign(size_t(colourTilesX_) * colourTilesY_, 0);
	warpedTiles_.assign(tileSources_.size(), 0);
	noTiles_.assign(tileSources_.size(), 0);
	for (Written &w : written_) {
		w.tag = 0;
		w.warpedTiles.assign(tileSources_.size(), 0);
	}
	clearTiles_.assign(tileSources_.size(), 0);
	copyTiles_.assign(tileSources_.size(), 0);
	runs_.reserve(size_t(tilesX_));
	for (int y = 0; y < outputHeight_; ++y)
		for (int x = 0; x < outputWidth_; ++x) {
			int32_t k = index_[size_t(y) * outputWidth_ + x];
			if (k == kOutsideView)
				continue;
			TileSources &t = tileSources_[size_t(y / kBoardTile) * tilesX_ + x / kBoardTile];
			int sx = k % colourWidth_, sy = k / colourWidth_;
			t.x0 = uint16_t(std::min<int>(t.x0, sx / kColourTile));
			t.y0 = uint16_t(std::min<int>(t.y0, sy / kColourTile));
			t.x1 = uint16_t(std::max<int>(t.x1, (sx + 1) / kColourTile));
			t.y1 = uint16_t(std::max<int>(t.y1, (sy + 1) / kColourTile));
		}
	for (TileSources &t : tileSources_)
		if (t.x0 == 0xFFFF)
			t = TileSources{}; // nothing seen: never warped
}

namespace {

// Whether any of the n pixels from p has alpha: two pixels per 64-bit word,
// a whole tile's eight in four loads.
bool anyAlpha(const Rgba8 *p, int n)
{
	constexpr uint64_t kAlphaBytes = 0xFF000000FF000000ull;
	uint64_t w[4] = {};
	if (n == 8) {
		std::memcpy(w, p, sizeof w);
		return ((w[0] | w[1] | w[2] | w[3]) & kAlphaBytes) != 0;
	}
	uint8_t any = 0;
	for (int i = 0; i < n; ++i)
		any |= p[i].a;
	return any != 0;
}

} // namespace

// Which colour tiles of the ROI hold some alpha (the source's alpha bytes).
// A tile at a time, row by row, stopping at the first row with alpha: the
// tiles the lecturer covers are known from their first row, and only the
// empty ones are read whole (a byte-by-byte or of every ROI pixel into
// occupied_ was a tenth of the frame's time; a word-wise one of every pixel,
// a twentieth).
void BoardCompositor::markOccupied(const RgbaImage &source, const Roi &roi)
{
	std::fill(occupied_.begin(), occupied_.end(), uint8_t(0));
	for (int ty = roi.y0 / kColourTile; ty * kColourTile < roi.y1; ++ty) {
		const int y0 = std::max(roi.y0, ty * kColourTile), y1 = std::min(roi.y1, (ty + 1) * kColourTile);
		uint8_t *tiles = occupied_.data() + size_t(ty) * colourTilesX_;
		for (int tx = roi.x0 / kColourTile; tx * kColourTile < roi.x1; ++tx) {
			const int x0 = std::max(roi.x0, tx * kColourTile), x1 = std::min(roi.x1, (tx + 1) * kColourTile);
			bool any = false;
			for (int y = y0; y < y1 && !any; ++y)
				any = anyAlpha(source.row(y) + x0, x1 - x0);
			tiles[tx] = any;
		}
	}
}

bool BoardCompositor::tileOccupied(const TileSources &t) const
{
	for (int ty = t.y0; ty <= t.y1 && ty < colourTilesY_; ++ty)
		for (int tx = t.x0; tx <= t.x1 && tx < colourTilesX_; ++tx)
			if (occupied_[size_t(ty) * colourTilesX_ + tx])
				return true;
	return false;
}

void BoardCompositor::clear()
{
	outputWidth_ = outputHeight_ = colourWidth_ = colourHeight_ = 0;
	index_.clear();
	frac_.clear();
	tileSources_.clear();
	occupied_.clear();
	warpedTiles_.clear();
	noTiles_.clear();
	for (Written &w : written_) {
		w.tag = 0;
		w.warpedTiles.clear();
	}
	clearTiles_.clear();
	copyTiles_.clear();
	runs_.clear();
	warped_ = Roi{};
	imageTag_ = 0;
}

const BoardCompositor::Written *BoardCompositor::writtenAs(uint64_t tag) const
{
	if (tag == 0)
		return nullptr;
	for (const Written &w : written_)
		if (w.tag == tag)
			return &w;
	return nullptr;
}

// The oldest entry makes room: its target was written kRemembered frames
// ago, longer than any ring keeps a slot.
void BoardCompositor::remember(uint64_t tag)
{
	Written &w = written_[nextWritten_];
	nextWritten_ = (nextWritten_ + 1) % kRemembered;
	w.tag = tag;
	w.boardVersion = boardVersion_;
	std::copy(warpedTiles_.begin(), warpedTiles_.end(), w.warpedTiles.begin());
}

// The board pixels whose bilinear footprint can touch the colour ROI: the
// ROI grown by one pixel (a sample up to a pixel outside reads its edge),
// mapped along its border. H maps straight edges to straight edges, so
// with a pinhole the corners bound it; a lens bends the edges, so then
// points along them are mapped too and a pixel of margin added.
Roi BoardCompositor::boardRoiOf(const Roi &colourRoi) const
{
	if (colourRoi.empty())
		return {};
	const double x0 = colourRoi.x0 - 1.5, x1 = colourRoi.x1 + 0.5;
	const double y0 = colourRoi.y0 - 1.5, y1 = colourRoi.y1 + 0.5;
	const int steps = lens_.isPinhole() ? 1 : 16;
	const double margin = lens_.isPinhole() ? 0 : 1;
	double minU = 1e18, maxU = -1e18, minV = 1e18, maxV = -1e18;
	for (int edge = 0; edge < 4; ++edge)
		for (int i = 0; i < steps; ++i) {
			const double t = double(i) / steps;
			const double cx[4] = { x0 + t * (x1 - x0), x1, x1 - t * (x1 - x0), x0 };
			const double cy[4] = { y0, y0 + t * (y1 - y0), y1, y1 - t * (y1 - y0) };
			double ix, iy, u, v;
			if (!lens_.undistort(cx[edge], cy[edge], ix, iy) || !colourToOutput_.apply(ix, iy, u, v))
				return { 0, 0, outputWidth_, outputHeight_ }; // beyond the horizon: all of it
			minU = std::min(minU, u - margin);
			maxU = std::max(maxU, u + margin);
			minV = std::min(minV, v - margin);
			maxV = std::max(maxV, v + margin);
		}
	auto clampTo = [](double v, int hi) { return int(std::clamp(v, 0.0, double(hi))); };
	Roi r{ clampTo(std::floor(minU), outputWidth_), clampTo(std::floor(minV), outputHeight_),
	       clampTo(std::ceil(maxU) + 1, outputWidth_), clampTo(std::ceil(maxV) + 1, outputHeight_) };
	return r.empty() ? Roi{} : r;
}

void BoardCompositor::compose(const RgbaImage &source, const Roi &roi, const RgbImage &board, int opacityQ8,
			      RgbImage &composite, RgbaImage &lecturer)
{
	composite.resize(outputWidth_, outputHeight_);
	lecturer.resize(outputWidth_, outputHeight_);
	// Another buffer (or a reallocated one) holds nothing we wrote.
	if (composite.data() != lastComposite_ || lecturer.data() != lastLecturer_) {
		imageTag_ = 0;
		lastComposite_ = composite.data();
		lastLecturer_ = lecturer.data();
	}
	imageTag_ = compose(source, roi, board, opacityQ8, { viewOf(composite), viewOf(lecturer), imageTag_ });
}

// The images' pair is known by its tag like a slot: the rows' history
// brings it up to date too.
void BoardCompositor::forgetBoardRows(int firstRow, int lastRow)
{
	if (firstRow > lastRow)
		return;
	boardVersion_++;
	boardChanges_[boardVersion_ % kBoardHistory] = { firstRow, lastRow };
}

BoardCompositor::Rows BoardCompositor::boardRowsChangedSince(uint64_t since) const
{
	if (since == boardVersion_)
		return {};
	if (since > boardVersion_ || boardVersion_ - since >= kBoardHistory)
		return { 0, INT_MAX }; // too long ago to know: all of it
	Rows rows{ INT_MAX, -1 };
	for (uint64_t v = since + 1; v <= boardVersion_; ++v) {
		const Rows &changed = boardChanges_[v % kBoardHistory];
		rows.first = std::min(rows.first, changed.first);
		rows.last = std::max(rows.last, changed.last);
	}
	return rows;
}

uint64_t BoardCompositor::compose(const RgbaImage &source, const Roi &roi, const RgbImage &board, int opacityQ8,
				  const BoardTarget &target)
{
	const int w = outputWidth_, h = outputHeight_;
	const ImageView<Rgb8> &composite = target.composite;
	const ImageView<Rgba8> &lecturer = target.lecturer;
	const bool targetFits = composite.width == w && composite.height == h && lecturer.width == w && lecturer.height == h;
	if (!configured() || !targetFits || source.width() != colourWidth_ || source.height() != colourHeight_ ||
	    board.width() != w || board.height() != h) {
		// Sizes that do not fit the map: the board alone (the caller
		// reconfigures; this never reads or writes out of bounds).
		const bool boardFits = board.width() == composite.width && board.height() == composite.height;
		for (int y = 0; y < composite.height && boardFits; ++y)
			std::memcpy(composite.row(y), board.row(y), size_t(composite.width) * sizeof(Rgb8));
		for (int y = 0; y < lecturer.height; ++y)
			std::fill(lecturer.row(y), lecturer.row(y) + lecturer.width, Rgba8{ 0, 0, 0, 0 });
		return 0;
	}
	const Roi clampedRoi{ std::max(roi.x0, 0), std::max(roi.y0, 0), std::min(roi.x1, colourWidth_),
			      std::min(roi.y1, colourHeight_) };
	warped_ = boardRoiOf(clampedRoi);
	markOccupied(source, clampedRoi);
	// The board tiles warped this frame: those in the ROI's reach whose
	// colour tiles hold alpha.
	std::fill(warpedTiles_.begin(), warpedTiles_.end(), uint8_t(0));
	const int tx0 = warped_.x0 / kBoardTile, tx1 = (warped_.x1 + kBoardTile - 1) / kBoardTile;
	const int ty0 = warped_.y0 / kBoardTile, ty1 = (warped_.y1 + kBoardTile - 1) / kBoardTile;
	for (int ty = ty0; ty < ty1; ++ty)
		for (int tx = tx0; tx < tx1; ++tx) {
			const size_t t = size_t(ty) * tilesX_ + tx;
			warpedTiles_[t] = tileOccupied(tileSources_[t]);
		}
	// What the target holds: transparent but where the tiles warped into
	// it last were, and (the same board picture) the board there too.
	const Written *before = writtenAs(target.holds);
	const Rows stale = before ? boardRowsChangedSince(before->boardVersion) : Rows{ 0, INT_MAX };
	const std::vector<uint8_t> &lastWarpedTiles = before ? before->warpedTiles : noTiles_;
	// The layer: clear the tiles warped last time that this frame does
	// not warp over (a whole 1920x1080 RGBA clear would cost a third of
	// the warp), or all of it when the target is unknown.
	// The composite likewise, with the board: copied where it last warped
	// (or all of it, into an unknown target), and in the rows of tiles
	// where the board changed since the target's picture.
	for (size_t t = 0; t < copyTiles_.size(); ++t) {
		const int rowTop = int(t / size_t(tilesX_)) * kBoardTile;
		const bool boardStale = rowTop <= stale.last && rowTop + kBoardTile - 1 >= stale.first;
		copyTiles_[t] = !warpedTiles_[t] && (boardStale || lastWarpedTiles[t]);
		clearTiles_[t] = !warpedTiles_[t] && (!before || lastWarpedTiles[t]);
	}
	warpedPixels_ = 0;
	const BoardWarpRowFn warpRow = boardWarpRowFn(path_);
	for (int ty = 0; ty < tilesY_; ++ty) {
		const int y0 = ty * kBoardTile, y1 = std::min(h, y0 + kBoardTile);
		for (const Run &run : runsOf(clearTiles_.data() + size_t(ty) * tilesX_))
			if (run.on)
				for (int y = y0; y < y1; ++y)
					std::memset(lecturer.row(y) + run.x0, 0, size_t(run.x1 - run.x0) * sizeof(Rgba8));
		// The composite: the board copied where it is not there yet, or
		// warped over, each byte at most once. One kernel call per pixel
		// row and run of warped tiles.
		for (const Run &run : runsOf(copyTiles_.data() + size_t(ty) * tilesX_))
			if (run.on)
				for (int y = y0; y < y1; ++y)
					std::memcpy(composite.row(y) + run.x0, board.row(y) + run.x0, size_t(run.x1 - run.x0) * sizeof(Rgb8));
		for (const Run &run : runsOf(warpedTiles_.data() + size_t(ty) * tilesX_)) {
			if (!run.on)
				continue;
			warpedPixels_ += size_t(run.x1 - run.x0) * (y1 - y0);
			for (int y = y0; y < y1; ++y) {
				const size_t k = size_t(y) * w + run.x0;
				warpRow({ index_.data() + k, frac_.data() + k, source.data(), colourWidth_, board.row(y) + run.x0,
					  composite.row(y) + run.x0, lecturer.row(y) + run.x0, run.x1 - run.x0 },
					opacityQ8);
			}
		}
	}
	const uint64_t tag = nextTag_++;
	remember(tag);
	return tag;
}

const std::vector<BoardCompositor::Run> &BoardCompositor::runsOf(const uint8_t *flags)
{
	runs_.clear();
	for (int tx = 0; tx < tilesX_;) {
		int end = tx + 1;
		while (end < tilesX_ && flags[end] == flags[tx])
			++end;
		runs_.push_back({ tx * kBoardTile, std::min(outputWidth_, end * kBoardTile), flags[tx] != 0 });
		tx = end;
	}
	return runs_;
}

} // namespace depthkey
