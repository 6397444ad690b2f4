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
// last frame's warped tiles were (the warp writes its pixels whole). A new
// board picture (forgetBoard()) is copied whole once: at 1920x1080 that
// copy is about a quarter of such a frame's time (docs/board.md), and the
// board's picture changes far less often than the camera's (a capture
// stick's every frame). Nothing is allocated per frame
// (tests/board_compositor_test.cpp counts).
#pragma once

#include "algo/homography.hpp"
#include "algo/image.hpp"
#include "algo/kernel_path.hpp"
#include "algo/trimap.hpp"

#include "algo/radial_lens.hpp"

#include <cstdint>
#include <vector>

namespace depthkey {

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

	// compose() clears only the tiles it warped into lecturer last time: call this
	// when lecturer was written by anyone else (the next compose clears all).
	void forgetLayer() { layerValid_ = false; }
	// compose() copies the board only where it warped last time: call this
	// when the board picture changed, or composite was written by anyone
	// else (the next compose copies all of it).
	void forgetBoard() { compositeValid_ = false; }

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
	std::vector<uint8_t> warpedTiles_, lastWarpedTiles_, clearTiles_, copyTiles_; // per board tile
	std::vector<Run> runs_;                // runsOf()'s, capacity tilesX_
	std::vector<int32_t> index_;       // per output pixel: top-left source pixel, kOutsideView = unseen
	std::vector<uint16_t> frac_;       // per output pixel: Q8 fx | fy << 8
	Roi warped_;
	size_t warpedPixels_ = 0;
	bool layerValid_ = false;          // lecturer is transparent outside lastWarpedTiles_
	bool compositeValid_ = false;      // composite is the board outside lastWarpedTiles_
	const void *lastComposite_ = nullptr, *lastLecturer_ = nullptr; // the buffers those hold for
};

} // namespace depthkey
