// What happens in the simulated lecture, as a function of time: a cycle in
// which the lecturer talks to the audience, walks to the board, writes two
// lines, turns and talks with gestures, writes elsewhere, wipes the first
// text off, writes again, and ends with a slide change. The cycle repeats
// with another slide and (seeded) other text positions.
//
// The board's content is baked into a texel raster per cycle: each texel
// knows when ink arrives and when it is wiped, so showing the board at any
// time is one comparison per pixel.
#pragma once

#include "hal/sim/scene_geometry.hpp"

#include <cstdint>
#include <vector>

namespace depthkey::sim {

enum class LecturerAction { Talk, Walk, Write, Erase };

struct ScriptPhase {
	LecturerAction action = LecturerAction::Talk;
	double start = 0, end = 0;     // cycle time, s
	double x0 = 0, x1 = 0;         // pelvis x at start and end (m)
	double z0 = 0, z1 = 0;         // pelvis depth at start and end (m)
	double yaw = 0;                // 0 faces the camera, pi the board
	int session = -1;              // Write/Erase: which text block
};

// One board texel: the slide's colour, the ink and when it is visible.
struct BoardTexel {
	Rgb8 background{};
	uint8_t ink = 0;               // 0 = none, else index into inkColours()
	uint16_t writeTick = 0;        // 10 ms ticks since the cycle started
	uint16_t eraseTick = 0;        // ink visible in [writeTick, eraseTick)
};

class LectureScript
{
public:
	static constexpr double kTickS = 0.01;

	void configure(uint64_t seed, double boardDistanceM, double walkSpeedMps, bool boardChanges);

	double cycleLength() const { return cycleLength_; }
	uint64_t cycleOf(double timeS) const;
	double cycleTime(double timeS) const;  // time within the cycle
	const ScriptPhase &phaseAt(double cycleTime) const;
	const ScriptPhase *previousPhase(const ScriptPhase &phase) const;

	// Where the writing hand is during a Write or Erase phase, in the board
	// plane (x, y); false while the pen is lifted (between lines).
	bool handOnBoard(const ScriptPhase &phase, double cycleTime, double &x, double &y) const;

	// The board as it is during cycle number `cycle` (the slide differs).
	void rasterise(uint64_t cycle, std::vector<BoardTexel> &texels) const;
	static const Rgb8 *inkColours(); // index 1..3

	bool boardChanges() const { return boardChanges_; }
	double boardDistance() const { return boardDistance_; }

private:
	struct Session {
		double left = 0, top = 0;      // first line's start in the board plane
		int colour = 1;
		double wordStart[8]{}, wordEnd[8]{}; // per line: pen-down spans (fraction of width)
		int words = 0;
	};
	bool penPosition(int session, double localTime, double &x, double &y, double &lineX) const;
	double writeDuration() const;
	void addPhase(LecturerAction action, double duration, double x1, double z1, double yaw, int session);
	void walkTo(double x, double z);

	uint64_t seed_ = 1;
	double boardDistance_ = 2.0;
	double walkSpeed_ = 1.0;
	bool boardChanges_ = true;
	double cycleLength_ = 0;
	std::vector<Session> sessions_;
	std::vector<ScriptPhase> phases_;
	double eraseLeft_ = 0, eraseRight_ = 0, eraseStart_ = 0, eraseEnd_ = 0;
};

} // namespace depthkey::sim
