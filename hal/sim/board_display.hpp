// The simulated board's display as the electronic board itself delivers it
// (board.backend "sim"): the slide and the strokes the simulated lecturer
// writes, crisp, without the lecturer, the camera's blur or the ToF. Its
// pixels span the display area of hal/sim/scene_geometry.hpp (3.2 x 1.3 m)
// with square pixels: a picture `width` wide is simBoardHeight(width) high.
//
// It is also where the simulator's truth of the board calibration lives:
// which board pixel a colour pixel sees (the display is the plane z = board
// distance in the colour camera's frame), and the homography that is exact
// when the colour lens has no distortion.
#pragma once

#include "algo/homography.hpp"
#include "algo/image.hpp"
#include "hal/sim/camera_rig.hpp"
#include "hal/sim/lecture_script.hpp"
#include "settings/settings.hpp"

#include <vector>

namespace depthkey {

int simBoardHeight(int width);

class SimBoardDisplay
{
public:
	void configure(const SimSettings &settings, int width);
	int width() const { return width_; }
	int height() const { return height_; }
	// The display at scene time timeS (the same clock as the sim cameras').
	void render(double timeS, RgbImage &out);

private:
	sim::LectureScript script_;
	bool boardChanges_ = true;
	int width_ = 0, height_ = 0;
	std::vector<int32_t> texelOf_; // per board pixel
	std::vector<sim::BoardTexel> texels_;
	uint64_t cycle_ = ~0ull;
};

// The board point (board px of a width x height picture) that colour pixel
// (x, y) sees on the display plane, through the lens as it is (distortion
// included); false when the ray misses the plane.
bool simColourToBoard(const CameraRig &rig, double boardDistanceM, int width, int height, double x, double y,
		      double &u, double &v);
// The exact homography colour px -> board px of a pinhole colour lens (the
// truth when [sim] distortion = false; with distortion the best H is only
// close to the mapping above).
Homography simTrueHomography(const CameraRig &rig, double boardDistanceM, int width, int height);

} // namespace depthkey
