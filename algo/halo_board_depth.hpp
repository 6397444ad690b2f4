// What the board reads beside the lecturer through the ToF's scattered-light
// halo (the paper's artefact; tof_artefacts in the simulator). Light from
// the near, bright lecturer scatters inside the camera onto the pixels
// around him, so a board pixel there measures a mix of its own depth and
// his: the more of him around it, the more (a straight silhouette covers
// half of a pixel's neighbourhood; the board enclosed between his arm and
// his side, or between his legs, is covered on most sides). Keyed against
// the board's true depth, such a pixel looks like the lecturer, in range and
// even inside the eroded subset, and depth outvotes the colour that says
// board. So the depth evidence compares a pixel with the board as the halo
// lets it read there:
//   zB' = zB - f (zB - zS),  f = share * min(1, 2 * cover)
// with cover the lecturer's share of the (2 halo_px + 1)^2 box around the
// pixel and zS his mean depth in that box. A first-order model of the
// scatter (the literature subtracts a point-spread function in phasor
// space, Mure-Dubois and Hügli 2007, which needs the camera's PSF); the
// technician sets halo_px and halo_share ([segmentation]).
// Fixed point: share and f in Q8, depths in mm, rounded to nearest;
// tests/halo_board_depth_test.cpp compares it with a double reference.
#pragma once

#include <algorithm>
#include <cstdint>

namespace depthkey {

// zBoardMm: the board's depth at the pixel; lecturerSumMm and lecturerCount:
// the sum of his depths and how many of his pixels lie in the box of
// boxArea pixels; shareQ8: the scattered share where he covers half the
// box or more (0 = no halo, at most 230 = 0.9). Returns the depth the board
// reads there, never nearer than his mean depth.
inline int haloBoardDepthMm(int zBoardMm, uint32_t lecturerSumMm, uint32_t lecturerCount, uint32_t boxArea,
			    int shareQ8)
{
	if (lecturerCount == 0 || shareQ8 <= 0 || boxArea == 0)
		return zBoardMm;
	const int zS = int((lecturerSumMm + lecturerCount / 2) / lecturerCount);
	if (zBoardMm <= zS)
		return zBoardMm;
	// min(1, 2 cover) in Q8, then f = share x that.
	const int coverQ8 = int(std::min<uint64_t>(256, (uint64_t(lecturerCount) * 512 + boxArea / 2) / boxArea));
	const int f = (std::min(shareQ8, 230) * coverQ8 + 128) >> 8;
	return zBoardMm - ((f * (zBoardMm - zS) + 128) >> 8);
}

} // namespace depthkey
