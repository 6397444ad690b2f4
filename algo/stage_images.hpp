// Named pictures of the pipeline's stages, for a technician tuning the
// config (depthkey-eval --preview, depthkeyd --preview and SIGUSR1). The
// pipeline lists what it has (borrowed, no copies); the writer
// (daemon/snapshot_writer.hpp) draws each by its kind: depth in false
// colour, seeds in three colours, masks in grey.
#pragma once

#include "algo/image.hpp"

#include <deque>
#include <string>
#include <vector>

namespace depthkey {

enum class StageKind {
	Colour,     // RgbImage as seen
	Depth,      // Gray16Image, millimetres, 0 = no measurement
	Seeds,      // Gray8Image of kSeed* values
	Mask,       // Gray8Image, 0 = board, 255 = lecturer (alpha: in between)
};

// Seed image values: what depth alone says about a colour pixel.
constexpr uint8_t kSeedBoard = 0;        // surely board
constexpr uint8_t kSeedUndecided = 128;  // the band colour segmentation decides
constexpr uint8_t kSeedLecturer = 255;   // surely lecturer

struct StageImage {
	std::string name;   // file stem, e.g. "depth-mapped"
	StageKind kind;
	const RgbImage *rgb = nullptr;
	const Gray16Image *depth = nullptr;
	const Gray8Image *gray = nullptr;
};

class StageImages
{
public:
	void add(std::string name, const RgbImage &image) { items_.push_back({ std::move(name), StageKind::Colour, &image }); }
	void addDepth(std::string name, const Gray16Image &image)
	{
		items_.push_back({ std::move(name), StageKind::Depth, nullptr, &image });
	}
	void add(std::string name, StageKind kind, const Gray8Image &image)
	{
		items_.push_back({ std::move(name), kind, nullptr, nullptr, &image });
	}
	// An image derived only for the preview, kept alive here.
	Gray8Image &ownGray(std::string name, StageKind kind)
	{
		owned_.emplace_back();
		add(std::move(name), kind, owned_.back());
		return owned_.back();
	}

	const std::vector<StageImage> &items() const { return items_; }
	void clear()
	{
		items_.clear();
		owned_.clear();
	}

private:
	std::vector<StageImage> items_;
	std::deque<Gray8Image> owned_;
};

} // namespace depthkey
