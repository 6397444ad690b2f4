#include "hal/sim/tof_artefacts.hpp"

#include "hal/sim/hash_noise.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace depthkey::sim {

namespace {

// Box blur of radius r over a width x height image, in place (separable
// running sums; the border is treated as zero, i.e. no lecturer there).
void boxBlur(std::vector<float> &img, int width, int height, int r, std::vector<float> &scratch)
{
	const float norm = 1.0f / static_cast<float>(2 * r + 1);
	scratch.resize(std::max(width, height));
	for (int y = 0; y < height; ++y) {
		float *row = img.data() + static_cast<size_t>(y) * width;
		std::copy(row, row + width, scratch.begin());
		float sum = 0;
		for (int x = 0; x < std::min(r, width); ++x)
			sum += scratch[x];
		for (int x = 0; x < width; ++x) { // sum covers [x - r, x + r]
			if (x + r < width)
				sum += scratch[x + r];
			row[x] = sum * norm;
			if (x - r >= 0)
				sum -= scratch[x - r];
		}
	}
	for (int x = 0; x < width; ++x) {
		for (int y = 0; y < height; ++y)
			scratch[y] = img[static_cast<size_t>(y) * width + x];
		float sum = 0;
		for (int y = 0; y < std::min(r, height); ++y)
			sum += scratch[y];
		for (int y = 0; y < height; ++y) {
			if (y + r < height)
				sum += scratch[y + r];
			img[static_cast<size_t>(y) * width + x] = sum * norm;
			if (y - r >= 0)
				sum -= scratch[y - r];
		}
	}
}

uint16_t clampU16(double v)
{
	return static_cast<uint16_t>(std::clamp(std::lround(v), 0L, 65535L));
}

} // namespace

double tofSigmaM(double intensity, double amplitude)
{
	return kTofRangeM / std::sqrt(8.0) * std::sqrt(intensity) / (2.0 * amplitude);
}

double tofIntensity(double ambient, double amplitude)
{
	return ambient + 1.5 * amplitude;
}

void TofAccumulator::reset(int w, int h)
{
	width = w;
	height = h;
	samples = 0;
	size_t n = static_cast<size_t>(w) * h;
	for (std::vector<float> *v : { &amplitude, &amplitudeZ, &lecturerAmp, &lecturerAmpZ, &lecturerCover })
		v->assign(n, 0.0f);
	nearestZ.assign(n, std::numeric_limits<float>::max());
}

void finishTofFrame(TofAccumulator &acc, const SimSettings &settings, uint64_t noiseKey, DepthFrame &out)
{
	const int w = acc.width, h = acc.height;
	const size_t n = static_cast<size_t>(w) * h;
	out.depthMm.resize(w, h);
	out.amplitude.resize(w, h);
	out.intensity.resize(w, h);

	const int r = settings.haloWidthPx;
	const bool halo = r > 0 && settings.haloStrength > 0;
	if (halo) {
		acc.blurA = acc.lecturerAmp;
		acc.blurAZ = acc.lecturerAmpZ;
		acc.blurCover = acc.lecturerCover;
		boxBlur(acc.blurA, w, h, r, acc.rowScratch);
		boxBlur(acc.blurAZ, w, h, r, acc.rowScratch);
		boxBlur(acc.blurCover, w, h, r, acc.rowScratch);
	}
	const float perSample = 1.0f / static_cast<float>(std::max(acc.samples, 1));
	const double saturationM = settings.saturationMm / 1000.0;
	for (size_t i = 0; i < n; ++i) {
		if (settings.saturationMm > 0 && acc.nearestZ[i] < saturationM) {
			out.depthMm.data()[i] = 0;
			out.amplitude.data()[i] = 65535;
			out.intensity.data()[i] = 65535;
			continue;
		}
		double amp = acc.amplitude[i] * perSample;
		double z = acc.amplitude[i] > 0 ? acc.amplitudeZ[i] / acc.amplitude[i] : 0.0;
		if (halo && acc.blurA[i] > 0) {
			// Scattered share: the halo strength where the lecturer covers
			// half of the box (a straight silhouette), fading to 0 at r.
			// Pixels the lecturer covers themselves are not changed by it.
			double cover = acc.blurCover[i] * perSample;
			double own = acc.lecturerCover[i] * perSample;
			double f = std::min(0.9, settings.haloStrength * std::min(1.0, 2.0 * cover) * (1.0 - own));
			double scatterZ = acc.blurAZ[i] / acc.blurA[i];
			z = (1.0 - f) * z + f * scatterZ;
			amp /= (1.0 - f); // the scattered light is received too
		}
		double intensity = tofIntensity(settings.tofAmbient, amp);
		if (settings.depthNoise && amp > 0)
			z += tofSigmaM(intensity, amp) * gaussianFromHash(hashKey(noiseKey, i));
		out.depthMm.data()[i] = amp > 0 ? std::max<uint16_t>(1, clampU16(z * 1000.0)) : 0;
		out.amplitude.data()[i] = clampU16(amp);
		out.intensity.data()[i] = clampU16(intensity);
	}
}

} // namespace depthkey::sim
