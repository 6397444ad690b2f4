// The simulated lecturer: head, hair, neck, two torso halves, legs, upper
// arms, forearms and hands as capsules, posed from the lecture script. The
// two torso halves make the silhouette narrow when the lecturer turns
// sideways; two-bone arms reach the pen point, so the writing hand touches
// the board (the case depth alone cannot separate).
#pragma once

#include "hal/sim/lecture_script.hpp"
#include "hal/sim/scene_geometry.hpp"

#include <vector>

namespace depthkey::sim {

// Clothing and skin, chosen by seed. Some seeds dress the lecturer close to
// the board (dark) or to the chalk (white) to make colour segmentation work.
struct LecturerLook {
	Rgb8 skin, hair, shirt, sleeves, trousers;
	static LecturerLook fromSeed(uint64_t seed);
};

constexpr int kLecturerCapsules = 14;

// Poses the lecturer at timeS into out (resized to kLecturerCapsules),
// in the colour camera's frame.
void poseLecturer(const LectureScript &script, const LecturerLook &look, double timeS,
		  std::vector<Capsule> &out);

} // namespace depthkey::sim
