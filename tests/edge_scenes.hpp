// Inputs for the stages that work along the decided edge (guided filter,
// boundary unmixing; issue 28): frames of the simulated lecture with a hard
// matte the way the pipeline decides it, the lecturer's true silhouette in
// ToF-sized steps (the edge off the colour image's, as mapped depth puts it)
// with a few specks; and the sizes and ROIs whose borders a kernel that
// follows the edge could get wrong.
#pragma once

#include "algo/image.hpp"
#include "algo/trimap.hpp"
#include "hal/sim/lecture_simulator.hpp"
#include "settings/settings.hpp"

#include <random>
#include <vector>

namespace depthkey::test {

struct EdgeScene {
	RgbImage colour;
	Gray8Image matte; // 0 or 255
	RgbImage room;    // the same view without the lecturer (the board)
};

// The lecture at timeS, w x h (any size, odd ones too), the matte's steps
// `step` pixels wide.
inline EdgeScene lectureEdgeScene(int w, int h, double timeS, int step = 4, unsigned seed = 1)
{
	LectureSimulator simulator;
	simulator.configure(Settings().sim, w, h);
	ColourFrame frame;
	GroundTruth truth;
	simulator.renderColour(timeS, frame, &truth);
	EdgeScene scene{ frame.rgb, Gray8Image(w, h, 0), {} };
	simulator.setLecturerVisible(false);
	simulator.renderColour(timeS, frame);
	scene.room = frame.rgb;
	std::mt19937 random(seed);
	for (int y = 0; y < h; ++y)
		for (int x = 0; x < w; ++x) {
			const int sx = std::min(w - 1, x / step * step + step / 2), sy = std::min(h - 1, y / step * step + step / 2);
			const bool speck = random() % 2000 == 0;
			scene.matte.at(x, y) = (truth.mask.at(sx, sy) != 0) != speck ? 255 : 0;
		}
	return scene;
}

// ROIs of a w x h image: all of it, at each border and corner, smaller than
// a window, one pixel wide or high, and empty.
inline std::vector<Roi> edgeSceneRois(int w, int h)
{
	return { Roi{ 0, 0, w, h },
		 Roi{ w / 5, h / 7, w - w / 6, h - 3 },
		 Roi{ 0, h / 3, w / 2 + 1, h },
		 Roi{ w / 2 - 1, 0, w, h / 2 + 3 },
		 Roi{ w / 2, h / 2, w / 2 + 3, h / 2 + 2 },
		 Roi{ w / 2, 0, w / 2 + 1, h },
		 Roi{ 0, h / 2, w, h / 2 + 1 },
		 Roi{ w / 2, h / 2, w / 2, h / 2 + 5 } };
}

} // namespace depthkey::test
