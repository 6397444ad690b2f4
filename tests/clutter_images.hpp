// Colour frames with no calibration pattern in them but many dark blobs
// (issue 31 point 12): a field of dots, each as round and as large as a
// pattern circle, and uniform noise. They make a circle-grid detector test
// every blob, so they measure what the detection costs at its worst.
#pragma once

#include "algo/frames.hpp"

#include <cstdint>

namespace depthkey::test {

// Deterministic pseudo-random numbers (xorshift), the same on any machine.
inline uint32_t nextRandom(uint32_t &state)
{
	state ^= state << 13;
	state ^= state >> 17;
	state ^= state << 5;
	return state;
}

// count black dots of radius 3-5 px on white, at random places (they may
// touch).
inline RgbImage dotField(int width, int height, int count, uint32_t seed = 12345)
{
	RgbImage image(width, height);
	for (int y = 0; y < height; y++)
		for (int x = 0; x < width; x++)
			image.at(x, y) = Rgb8{ 255, 255, 255 };
	for (int i = 0; i < count; i++) {
		int r = 3 + int(nextRandom(seed) % 3);
		int cx = r + int(nextRandom(seed) % uint32_t(width - 2 * r));
		int cy = r + int(nextRandom(seed) % uint32_t(height - 2 * r));
		for (int y = cy - r; y <= cy + r; y++)
			for (int x = cx - r; x <= cx + r; x++)
				if ((x - cx) * (x - cx) + (y - cy) * (y - cy) <= r * r)
					image.at(x, y) = Rgb8{ 0, 0, 0 };
	}
	return image;
}

// Grey noise, each pixel uniform in 0..255.
inline RgbImage noiseImage(int width, int height, uint32_t seed = 777)
{
	RgbImage image(width, height);
	for (int y = 0; y < height; y++)
		for (int x = 0; x < width; x++) {
			uint8_t v = uint8_t(nextRandom(seed) >> 24);
			image.at(x, y) = Rgb8{ v, v, v };
		}
	return image;
}

} // namespace depthkey::test
