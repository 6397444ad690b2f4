// Depth seeding (paper 6.1), at the depth camera's resolution where it is
// cheap (160x124 on the SR-2):
//   trusted   = near <= depth <= far, min_amplitude <= amplitude < max_amplitude
//               (a weak echo says nothing, a saturated one lies);
//   subset    = the 4-connected component of erode(trusted, erode_px) that
//               is the lecturer (algo/lecturer_picker.hpp: he moves or is
//               where he was; a desk in range is furniture), eroded less
//               when the erosion leaves nothing of him: surely lecturer;
//   superset  = dilate(the in-range component holding the subset,
//               dilate_px); everything outside is surely board;
//   core      = erode(that in-range component, erode_px + core_px): fixed
//               as lecturer whatever colour says;
//   undecided = superset minus core, where the evidence decides, graded
//               by depth (algo/trimap.hpp): subset, in range, out of range;
//   evidence  = per superset pixel, how much better its depth fits the
//               lecturer's surface there than the board's learned depth
//               as the scattered-light halo lets it read beside him
//               (algo/halo_board_depth.hpp), given the ToF noise at that
//               pixel (depthEvidence below).
#pragma once

#include "algo/frames.hpp"
#include "algo/furniture_mask.hpp"
#include "algo/lecturer_picker.hpp"
#include "algo/morphology.hpp"
#include "algo/static_background.hpp"
#include "settings/settings.hpp"

#include <vector>

namespace depthkey {

struct DepthSeeds {
	Gray8Image labels;          // trimap labels (algo/trimap.hpp), ToF resolution
	// The depth each lecturer or undecided pixel is mapped into the colour
	// image with: the mean depth of the lecturer's in-range pixels within
	// surface_px (his surface there, without the ToF noise, which would
	// scatter neighbouring pixels by different parallaxes and leave gaps;
	// a radius beyond dilate_px reaches him from every band pixel, so the
	// whole band moves with him), else his mean depth. 0 on board pixels.
	Gray16Image surfaceMm;
	// What depth says of each superset pixel (depthEvidence): 128 neither,
	// higher lecturer, lower board; 0 outside the superset.
	Gray8Image evidence;
	int lecturerDepthMm = 0;    // mean depth of the surely-lecturer pixels; 0 = none
	int lecturerPixels = 0;
};

class DepthSeeder
{
public:

	void configure(const SegmentationSettings &segmentation);
	void setKernelPath(KernelPath path) { path_ = path; }

	// A frame whose images differ in size from each other gives no lecturer.
	void seed(const DepthFrame &depth, DepthSeeds &out);

	// The depth evidence of one pixel (the kernel, for tests): depth d is
	// the lecturer's surface zL plus noise, or the board's learned depth zB
	// plus noise, with the ToF's noise from amplitude A and intensity I
	// (the paper's model, sigma = L / sqrt(8) * sqrt(I) / (2 A), L = 7.5 m
	// at 20 MHz) plus kNoiseFloorMm. With equal variances the log-likelihood
	// ratio is linear in d:
	//   ln p(d | lecturer) / p(d | board) = (zB - zL) (zL + zB - 2 d) / (2 sigma^2)
	// in nats; kUnitsPerNat confidence units a nat, around 128, clamped to
	// 1..254. A mixed pixel at the silhouette (its depth between the two:
	// the scattered-light halo, motion blur) says little, a clean pixel
	// much, a pixel in the noisy image corner little. amplitude = 0: no
	// amplitude image, kNoAmplitudeSigmaMm instead. zB = 0: not learned,
	// the board is taken kUnknownBoardBehindMm behind him.
	static uint8_t depthEvidence(int dMm, int amplitude, int intensity, int zLecturerMm, int zBoardMm);
	static constexpr int kUnitsPerNat = 16;
	static constexpr int kNoiseFloorMm = 15;       // calibration, quantisation
	static constexpr int kNoAmplitudeSigmaMm = 50; // a Z16 camera without amplitude
	static constexpr int kUnknownBoardBehindMm = 450;
	// The least depth evidence of a core pixel: 2 nats for the lecturer.
	// Measured on the simulated lecture (all artefacts, seeds 1-3): the core's
	// wrong pixels fell from 3.1 % to 1.3 % of it, mean IoU / BF +0.004 /
	// +0.016; 160 to 200 score the same, 230 starts to lose the thin arm.
	static constexpr uint8_t kCoreMinEvidence = 128 + 2 * kUnitsPerNat;

private:
	SegmentationSettings settings_;
	KernelPath path_ = bestKernelPath();
	void smoothSurface(const Gray16Image &depthMm, DepthSeeds &out);
	void weighDepth(const DepthFrame &depth, DepthSeeds &out) const;
	static void keepCoreWhereDepthIsSure(DepthSeeds &out);
	// min_amplitude <= a < max_amplitude in one unsigned compare: a weak
	// echo says nothing, a saturated one lies.
	bool trustedEcho(unsigned a) const
	{
		return a - unsigned(settings_.minAmplitude) < unsigned(settings_.maxAmplitude - settings_.minAmplitude);
	}

	Gray8Image trusted_, subset_, reach_, superset_, core_, moving_;
	std::vector<uint32_t> depthSums_, counts_; // integral images, (w+1) x (h+1)
	StaticBackground background_;
	LecturerPicker picker_;
	FurnitureMask furniture_;
	MorphologyScratch morphology_;
	ComponentScratch components_;
};

} // namespace depthkey
