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
// else without clearing the whole image. lecturerBeyondBorder says whether
// surely-lecturer depth pixels fell outside the colour image (the depth
// camera sees wider): the lecturer reaches in over the image border, though
// no lecturer seed may lie inside. The depth evidence (DepthSeeds::evidence)
// is painted the same way beside the trimap.
#pragma once

#include "algo/depth_mapper.hpp"
#include "algo/depth_seeder.hpp"
#include "algo/kernel_path.hpp"
#include "algo/trimap.hpp"

#include <vector>

namespace depthkey {

// One depth frame's seeds in the colour image.
struct MappedSeeds {
	Gray8Image trimap;       // colour size; board outside roi
	Gray8Image evidence;     // DepthSeeds::evidence, colour size; 0 outside roi
	Roi roi;                 // the painted region (empty: no lecturer)
	bool lecturerBeyondBorder = false;

	// Board everywhere again at width x height, for the next painting:
	// only the last ROI is cleared (all of it when the size changed), and
	// roi becomes empty.
	void clear(int width, int height);
};

class SeedMapper
{
public:
	void configure(const DepthMapper &mapper);
	// The blocks' rows are max-painted by algo/max_paint_rows.hpp's rows of path.
	void setKernelPath(KernelPath path) { path_ = path; }

	// out.trimap is resized to the mapper's colour size; out.roi receives
	// the painted region (empty when there is no lecturer). Only out's
	// previous ROI is cleared: out must be kept from call to call.
	void map(const DepthSeeds &seeds, MappedSeeds &out) const;

	// Colour pixels one ToF pixel spans at the image centre, at the depth a
	// lecturer stands (1.5 m), rounded up: converts radii given in ToF pixels.
	int colourPixelsPerTofPixel() const;

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
	KernelPath path_ = bestKernelPath();
	std::vector<Footprint> footprints_;
};

} // namespace depthkey
