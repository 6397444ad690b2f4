// Named pictures of the pipeline's stages, for a technician tuning the
// config (depthkey-eval --preview, depthkeyd --preview and SIGUSR1). The
// pipeline lists what it has (borrowed, no copies); the writer
// (hal/preview/snapshot_writer.hpp) draws each by its kind: depth in false
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
	Seeds,      // Gray8Image of trimap labels (algo/trimap.hpp)
	Mask,       // Gray8Image, 0 = board, 255 = lecturer (alpha: in between)
};

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
	// Images derived only for the preview, kept alive here.
	Gray8Image &ownGray(std::string name, StageKind kind)
	{
		owned_.emplace_back();
		add(std::move(name), kind, owned_.back());
		return owned_.back();
	}
	Gray16Image &ownDepth(std::string name)
	{
		ownedDepth_.emplace_back();
		addDepth(std::move(name), ownedDepth_.back());
		return ownedDepth_.back();
	}

	const std::vector<StageImage> &items() const { return items_; }
	void clear()
	{
		items_.clear();
		owned_.clear();
		ownedDepth_.clear();
	}

private:
	std::vector<StageImage> items_;
	std::deque<Gray8Image> owned_;
	std::deque<Gray16Image> ownedDepth_;
};

} // namespace depthkey
