// Carries the depth seeds from ToF resolution into the colour image: each
// surely-lecturer or undecided ToF pixel is mapped (DepthMapper, at the
// lecturer's smoothed surface depth, DepthSeeds::surfaceMm) and painted as
// a block of its footprint (the colour-pixel step to its neighbouring ToF
// pixels at that depth, plus one pixel of overlap, so neighbouring blocks
// always touch, whatever the lenses' scales). Where
// blocks overlap the higher label wins (lecturer over undecided over board):
// the lecturer is the nearest surface in the scene, so this is the z-buffer's
// "nearest wins" without storing depths. Everything not painted is board.
//
// Only the region painted (the ROI, plus a one pixel border) is touched; the
// previous frame's ROI is cleared first, so the trimap is board everywhere
// else without clearing the whole image.
#pragma once

#include "algo/depth_mapper.hpp"
#include "algo/depth_seeder.hpp"
#include "algo/trimap.hpp"

#include <vector>

namespace depthkey {

class SeedMapper
{
public:
	void configure(const DepthMapper &mapper);

	// trimap is resized to the mapper's colour size; roi receives the
	// painted region (empty when there is no lecturer).
	void map(const DepthSeeds &seeds, Gray8Image &trimap, Roi &roi);

	// Colour pixels one ToF pixel spans at the image centre, at the depth a
	// lecturer stands (1.5 m), rounded up: converts radii given in ToF pixels.
	int colourPixelsPerTofPixel() const;

	// Whether the last map() found surely-lecturer depth pixels outside the
	// colour image (the depth camera sees wider): the lecturer reaches in
	// over the image border, though no lecturer seed may lie inside.
	bool lecturerBeyondBorder() const { return lecturerBeyondBorder_; }

private:
	// The footprint of each ToF pixel at depths 500, 750, ... 4000 mm (the
	// nearest is used): precomputed, it changes little with depth.
	static constexpr int kFootprintFirstMm = 500, kFootprintStepMm = 250, kFootprintBuckets = 15;
	struct Footprint {
		uint8_t w, h;
	};

	// The precomputed footprint of ToF pixel i at the bucket nearest zMm.
	const Footprint &footprint(int i, int zMm) const;

	const DepthMapper *mapper_ = nullptr;
	std::vector<Footprint> footprints_;
	Roi previous_;
	bool lecturerBeyondBorder_ = false;
};

} // namespace depthkey
