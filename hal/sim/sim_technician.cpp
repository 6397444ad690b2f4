#include "hal/sim/sim_technician.hpp"

#include <algorithm>

namespace depthkey::sim {

void SimTechnician::configure(const CameraRig &rig, const PatternBoard &board)
{
	std::lock_guard lock(mutex_);
	renderer_.configure(rig, board, PatternConditions{});
	board_ = board;
	holding_ = false;
}

void SimTechnician::holdAt(const PatternStep &step, int index, double nowS)
{
	std::lock_guard lock(mutex_);
	PatternPose next = renderer_.poseFor(step, index);
	if (!holding_) {
		from_ = next; // the first place: he stands there with it
	} else {
		// Wherever it is now (he may be told mid-way).
		double t = std::clamp((nowS - startS_) / kMoveS, 0.0, 1.0);
		from_.centre = from_.centre + t * (to_.centre - from_.centre);
		from_.yawDeg += t * (to_.yawDeg - from_.yawDeg);
		from_.pitchDeg += t * (to_.pitchDeg - from_.pitchDeg);
		from_.rollDeg += t * (to_.rollDeg - from_.rollDeg);
	}
	to_ = next;
	startS_ = nowS;
	holding_ = true;
}

std::optional<CalibrationTarget> SimTechnician::targetAt(double timeS) const
{
	std::lock_guard lock(mutex_);
	if (!holding_)
		return std::nullopt;
	// Smooth start and stop: still at both ends.
	double t = std::clamp((timeS - startS_) / kMoveS, 0.0, 1.0);
	t = t * t * (3 - 2 * t);
	PatternPose pose;
	pose.centre = from_.centre + t * (to_.centre - from_.centre);
	pose.yawDeg = from_.yawDeg + t * (to_.yawDeg - from_.yawDeg);
	pose.pitchDeg = from_.pitchDeg + t * (to_.pitchDeg - from_.pitchDeg);
	pose.rollDeg = from_.rollDeg + t * (to_.rollDeg - from_.rollDeg);
	return calibrationTarget(pose, board_);
}

} // namespace depthkey::sim
