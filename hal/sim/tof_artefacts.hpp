// The ToF camera's measurement, from the light its samples gathered to the
// three images it delivers, with the artefacts of paper section 3:
//  - scatter halo: light the lecturer throws onto the board nearby arrives
//    with the lecturer's phase, so board pixels around the silhouette read
//    closer (a box of haloWidthPx around the lecturer's coverage);
//  - saturation: nearer than saturationMm the pixel is blinded (depth 0,
//    amplitude and intensity 65535);
//  - noise: sigma = L / sqrt(8) * sqrt(I) / (2 A), L = 7.5 m, with the
//    intensity I = ambient + 1.5 A (the modulated light adds its own offset).
#pragma once

#include "algo/frames.hpp"
#include "settings/settings.hpp"

#include <vector>

namespace depthkey::sim {

constexpr double kTofRangeM = 7.5; // 20 MHz modulation

// sigma of one depth measurement, metres.
double tofSigmaM(double intensity, double amplitude);
// Intensity that goes with an amplitude (both camera units).
double tofIntensity(double ambient, double amplitude);

// Per ToF pixel sums over its spatial and time samples.
struct TofAccumulator {
	int width = 0, height = 0;
	int samples = 0;                 // samples summed per pixel
	std::vector<float> amplitude;    // sum A
	std::vector<float> amplitudeZ;   // sum A z (phase mixes by amplitude)
	std::vector<float> lecturerAmp;  // sum a A_lecturer
	std::vector<float> lecturerAmpZ; // sum a A_lecturer z_lecturer
	std::vector<float> lecturerCover;// sum a
	std::vector<float> nearestZ;     // nearest surface any sample saw, m
	std::vector<float> rowScratch, blurA, blurAZ, blurCover;

	void reset(int w, int h);
	void add(size_t pixel, float amp, float z)
	{
		amplitude[pixel] += amp;
		amplitudeZ[pixel] += amp * z;
		if (z < nearestZ[pixel])
			nearestZ[pixel] = z;
	}
};

// Turns the sums into out's depth, amplitude and intensity images.
// noiseKey selects the noise pattern (same key, same noise).
void finishTofFrame(TofAccumulator &acc, const SimSettings &settings, uint64_t noiseKey, DepthFrame &out);

} // namespace depthkey::sim
