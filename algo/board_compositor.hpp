// The lecturer laid over the board's own picture in the board's geometry
// (the paper's Figure 1): the colour camera sees the board's display as a
// quadrilateral, the homography H (colour px -> board px) says where each
// camera pixel lands on the board, and the lecturer's colour and alpha are
// warped there and blended over the board picture with composite.opacity,
// the same blend as the camera-geometry composite (algo/composite.hpp).
//
// The warp is a per-board-pixel map, precomputed once per H and size: the
// colour-image point each board pixel shows, in Q8 fixed point (a source
// index and the fractions), sampled bilinearly from the camera-geometry
// lecturer layer (RGBA: colour and alpha each straight, as the camera
// composite takes the camera's pixel as it is; algo/board_warp_rows.hpp).
// Only the board pixels the lecturer can reach are warped: the board is cut
// into 16x16 tiles, each knowing (from the map) the 8x8 colour tiles it
// reads, and a tile is warped only when one of those holds some alpha in
// this frame. Elsewhere the composite is the board and the board-geometry
// lecturer layer is transparent. Both outputs keep what they held: the
// layer is cleared, and the board copied into the composite, only where
// the tiles warped into that same pair of buffers last time were (the warp
// writes its pixels whole). The outputs may be the shared-memory ring's
// slots (issue 29 §2: each frame written once, where it goes), a pair for
// each slot, so the compositor remembers which tiles it warped into each of
// its last kRemembered pairs, known by the tag compose() returns. A new
// board picture is copied into each pair once, and only in the rows it
// changed (forgetBoardRows(); forgetBoard(): all of them): at 1920x1080 a
// whole copy is about a quarter of such a frame's time (docs/board.md),
// and a board's picture comes 10 times a second mostly unchanged, or with
// a stroke more. Nothing is allocated per frame
// (tests/board_compositor_test.cpp counts).
#pragma once

#include "algo/homography.hpp"
#include "algo/image.hpp"
#include "algo/image_view.hpp"
#include "algo/kernel_path.hpp"
#include "algo/trimap.hpp"

#include "algo/radial_lens.hpp"

#include <array>
#include <climits>
#include <cstdint>
#include <vector>

namespace depthkey {

// Where compose() writes, both of the output size: the composite (RGB) and
// the board-geometry lecturer layer (RGBA). holds: the tag compose()
// returned when it last wrote this pair, as it was left (0: unknown
// contents, written whole).
struct BoardTarget {
	ImageView<Rgb8> composite;
	ImageView<Rgba8> lecturer;
	uint64_t holds = 0;
};

class BoardCompositor
{
public:
	// colourToOutput maps ideal (undistorted by lens) colour pixels to
	// pixels of the output (the board picture at its output size); the lens
	// is folded into the per-pixel map, so it costs nothing per frame.
	// Allocates the map; false when H is singular or a size is empty (the
	// compositor is then unconfigured).
	bool configure(const Homography &colourToOutput, int colourWidth, int colourHeight, int outputWidth,
		       int outputHeight, const RadialLens &lens = RadialLens{});
	void clear();
	bool configured() const { return outputWidth_ > 0; }
	int outputWidth() const { return outputWidth_; }
	int outputHeight() const { return outputHeight_; }

	void setKernelPath(KernelPath path) { path_ = path; }

	// source: the colour camera's lecturer layer (RGBA, straight alpha, the
	// colour size), its alpha 0 outside roi (the pipeline's ROI). board must
	// be the output size. composite (RGB) and lecturer (RGBA) are resized to
	// the output size; lecturer is transparent outside the warped region.
	// Pass the same composite and lecturer images every frame (another
	// buffer, or a new size, is written whole), and say when the board
	// picture changed (forgetBoard()).
	void compose(const RgbaImage &source, const Roi &roi, const RgbImage &board, int opacityQ8,
		     RgbImage &composite, RgbaImage &lecturer);
	// The same into borrowed buffers of the output size (a ring slot's):
	// only what differs from the frame target.holds names is written.
	// Returns the tag of what the pair holds now, for the next compose()
	// into it; 0 when the sizes did not fit (the board alone written whole).
	uint64_t compose(const RgbaImage &source, const Roi &roi, const RgbImage &board, int opacityQ8,
			 const BoardTarget &target);

	// compose() clears only the tiles it warped into lecturer last time: call this
	// when the images were written by anyone else (the next compose writes all).
	void forgetLayer() { imageTag_ = 0; }
	// compose() copies the board only where it warped last time: call this
	// when the board picture changed, or composite was written by anyone
	// else (the next compose copies all of it, into every target).
	void forgetBoard()
	{
		forgetBoardRows(0, INT_MAX);
		imageTag_ = 0;
	}
	// Only the board's rows firstRow..lastRow (output rows) changed
	// (first > last: none): a target that held the board of up to
	// kBoardHistory pictures ago gets only the rows changed since copied.
	// The board's picture comes 10 times a second, mostly the one before
	// with a stroke more (algo/changed_rows.hpp); copying it whole into
	// each slot was the event loop's largest cost (15 %) after the warp.
	void forgetBoardRows(int firstRow, int lastRow);

	// The board pixels the last compose() warped (for tests and previews).
	const Roi &warpedRoi() const { return warped_; }
	// How many board pixels the last compose() ran the warp kernel on.
	size_t warpedPixels() const { return warpedPixels_; }

private:
	Roi boardRoiOf(const Roi &colourRoi) const;

	Homography colourToOutput_;
	RadialLens lens_;
	int colourWidth_ = 0, colourHeight_ = 0, outputWidth_ = 0, outputHeight_ = 0;
	static constexpr int kBoardTile = 16, kColourTile = 8;
	struct TileSources {
		uint16_t x0 = 1, y0 = 1, x1 = 0, y1 = 0; // colour tiles read, inclusive; empty when x0 > x1
	};
	void tileSources();
	bool tileOccupied(const TileSources &t) const;
	void markOccupied(const RgbaImage &source, const Roi &roi);
	// Runs of equal flags along one row of board tiles, as pixel columns.
	struct Run {
		int x0, x1;
		bool on;
	};
	const std::vector<Run> &runsOf(const uint8_t *flags); // valid until the next call

	KernelPath path_ = bestKernelPath();
	int tilesX_ = 0, tilesY_ = 0, colourTilesX_ = 0, colourTilesY_ = 0;
	std::vector<TileSources> tileSources_; // per board tile
	std::vector<uint8_t> occupied_;        // per colour tile: some alpha this frame
	std::vector<uint8_t> warpedTiles_, clearTiles_, copyTiles_; // per board tile
	std::vector<Run> runs_;                // runsOf()'s, capacity tilesX_
	std::vector<int32_t> index_;       // per output pixel: top-left source pixel, kOutsideView = unseen
	std::vector<uint16_t> frac_;       // per output pixel: Q8 fx | fy << 8
	Roi warped_;
	size_t warpedPixels_ = 0;
	// What compose() wrote into its last targets: a target holding tag is
	// transparent and (with the same board version) the board outside
	// warpedTiles. The ring's slots (up to 8) and the images' pair.
	struct Written {
		uint64_t tag = 0;
		uint64_t boardVersion = 0;
		std::vector<uint8_t> warpedTiles; // per board tile
	};
	static constexpr size_t kRemembered = 9;
	const Written *writtenAs(uint64_t tag) const; // null: not remembered
	void remember(uint64_t tag);
	std::array<Written, kRemembered> written_;
	size_t nextWritten_ = 0;
	uint64_t nextTag_ = 1;
	uint64_t boardVersion_ = 1;          // forgetBoard() moves it on
	// The rows each of the last board versions changed (index: version
	// modulo kBoardHistory), and those changed since version `since`.
	static constexpr uint64_t kBoardHistory = 16;
	struct Rows {
		int first = 1, last = 0;
	};
	std::array<Rows, kBoardHistory> boardChanges_{};
	Rows boardRowsChangedSince(uint64_t since) const;
	std::vector<uint8_t> noTiles_;       // all 0: what an unknown target had warped
	uint64_t imageTag_ = 0;              // what the images' pair holds
	const void *lastComposite_ = nullptr, *lastLecturer_ = nullptr; // the images imageTag_ is for
};

} // namespace depthkey
