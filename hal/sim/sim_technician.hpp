// The technician of a simulated calibration session, for
// `depthkey-calibrate --live` on the simulated cameras (hal/sim/sim_cameras.hpp):
// told where to hold the printed pattern (a step of algo/calibration_plan.hpp),
// he carries it there from where it was in moveS seconds (turning it as a hand
// does) and then holds it still until told the next place. The cameras ask
// where it is at their scene time; the lecturer stays away meanwhile.
#pragma once

#include "algo/calibration_plan.hpp"
#include "hal/sim/calibration_pattern.hpp"
#include "hal/sim/camera_rig.hpp"

#include <mutex>
#include <optional>

namespace depthkey::sim {

class SimTechnician
{
public:
	static constexpr double kMoveS = 0.8;

	// The pattern's poses are those of depthkey-calibrate --sim for this rig.
	void configure(const CameraRig &rig, const PatternBoard &board);

	// From nowS on he carries the pattern to step (the index-th of the plan).
	void holdAt(const PatternStep &step, int index, double nowS);

	// The pattern at scene time timeS; nothing before the first holdAt().
	std::optional<CalibrationTarget> targetAt(double timeS) const;

private:
	PatternRenderer renderer_;
	PatternBoard board_;
	mutable std::mutex mutex_; // the cameras may render on other threads one day
	bool holding_ = false;
	PatternPose from_, to_;
	double startS_ = 0;
};

} // namespace depthkey::sim
