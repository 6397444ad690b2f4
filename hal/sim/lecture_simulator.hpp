// The simulated lecture, renderable offline: depthkey-eval, the tests, the
// calibration tool and the emulated devices call it directly, the sim
// cameras call it from their timers. Deterministic: the pixels depend only
// on the settings (seed included) and the time asked for.
//
// Colour: the distorted webcam view, lit by a slowly varying room light,
// with sensor noise; ground truth = the lecturer's exact coverage.
// Depth: the ToF view at 160x124 (2x2 samples a pixel, so edge pixels mix
// depths), integrated over its exposure (motion blur), with the scatter halo
// around the lecturer, saturation when too near, and noise following
// sigma = L / sqrt(8) * sqrt(I) / (2 A); the depth, amplitude and intensity
// images are consistent with each other.
#pragma once

#include "algo/frames.hpp"
#include "hal/sim/camera_rig.hpp"
#include "hal/sim/colour_backdrop.hpp"
#include "hal/sim/lecture_script.hpp"
#include "hal/sim/lecturer_model.hpp"
#include "hal/sim/ray_grid.hpp"
#include "hal/sim/tof_artefacts.hpp"
#include "settings/settings.hpp"

#include <optional>

namespace depthkey {

// What the colour frame shows, exactly.
struct GroundTruth {
	Gray8Image mask;      // 255 where the lecturer covers at least half the pixel
	Gray8Image alpha;     // the lecturer's coverage, 0..255 (fractional at edges)
	Gray16Image depthMm;  // colour-frame z of the visible surface, mm
	double timeS = 0;
};

class LectureSimulator
{
public:
	static constexpr int kTofWidth = 160, kTofHeight = 124;

	void configure(const SimSettings &settings, int colourWidth, int colourHeight);

	const SimSettings &settings() const { return settings_; }
	const CameraRig &rig() const { return rig_; }

	// The colour picture at timeS (timestampNs = timeS), and its truth.
	void renderColour(double timeS, ColourFrame &out, GroundTruth *truth = nullptr);
	// The depth frame whose exposure is centred on timeS (timestampNs = timeS;
	// the caller adds the latency it models).
	void renderDepth(double timeS, DepthFrame &out);

	// Calibration (issue 7): with a target set, the lecturer leaves and the
	// target stands at its pose in front of the board, seen by both cameras
	// (colour picture and ToF amplitude); nullopt brings the lecture back.
	void setCalibrationTarget(const std::optional<sim::CalibrationTarget> &target);
	// Both views of a target at its pose (the calibration tool's shot): sets
	// the target, renders colour and depth at timeS; the target stays set.
	void renderCalibrationPattern(const sim::CalibrationTarget &target, double timeS, ColourFrame &colour,
				      DepthFrame &depth);
	// The board's display shows this picture (e.g. the board calibration
	// pattern, algo/board_pattern.hpp) over its whole area instead of the
	// slide and strokes; an empty picture brings them back. Each colour pixel
	// averages 4x4 bilinear samples of it, through the lens as it is.
	void showOnBoard(const RgbImage &picture);
	// An empty room (the board, the desk), e.g. to measure the ToF's noise.
	void setLecturerVisible(bool visible) { lecturerVisible_ = visible; }

	// The lecturer's capsules at timeS (colour frame), for tests and tools.
	void poseLecturer(double timeS, std::vector<sim::Capsule> &out) const;
	const sim::LectureScript &script() const { return script_; }

private:
	void ensureColourGrid();
	void ensureDepthGrid();
	void ensureBoard(double timeS);
	void lightingGains(double timeS, int gains[3]) const;

	SimSettings settings_;
	int colourWidth_ = 640, colourHeight_ = 480;
	CameraRig rig_;
	sim::LectureScript script_;
	sim::LecturerLook look_{};
	std::optional<sim::CalibrationTarget> target_;
	sim::RayGrid colourGrid_, depthGrid_;
	bool colourReady_ = false, depthReady_ = false;
	bool lecturerVisible_ = true;
	std::vector<sim::Capsule> capsules_;
	sim::ColourBackdrop backdrop_;       // per colour pixel: the board texel it shows, off the board its colour
	RgbImage shownPicture_;
	std::vector<Rgb8> shown_;            // per colour pixel, when shownPicture_ is set
	uint64_t boardCycle_ = ~0ull;
	int8_t colourNoise_[256]{};
	sim::TofAccumulator tof_;
	std::vector<float> staticAmplitude_; // per ToF sample: board etc. without lecturer
	std::vector<float> vignette_;        // per ToF pixel
};

} // namespace depthkey
