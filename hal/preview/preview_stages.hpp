// The stages the preview page shows, by the names of its URLs
// (/stream/composite.mjpg), and one encoded picture of a stage. The
// composite, the lecturer layer and the board are what the recorder gets
// (issue 30): the shared memory's pictures, in the board's geometry when it
// is calibrated; the others are the pipeline's stages.
#pragma once

#include <array>
#include <cstdint>
#include <string_view>
#include <vector>

namespace depthkey {

enum class PreviewStage { Colour, Depth, Seeds, Alpha, Composite, Lecturer, Board };
constexpr size_t kPreviewStageCount = 7;
constexpr std::array<std::string_view, kPreviewStageCount> kPreviewStageNames = {
	"colour", "depth", "seeds", "alpha", "composite", "lecturer", "board"
};

inline std::string_view previewStageName(PreviewStage stage)
{
	return kPreviewStageNames[static_cast<size_t>(stage)];
}

inline bool previewStageFromName(std::string_view name, PreviewStage &stage)
{
	for (size_t i = 0; i < kPreviewStageCount; i++)
		if (kPreviewStageNames[i] == name) {
			stage = static_cast<PreviewStage>(i);
			return true;
		}
	return false;
}

struct EncodedFrame {
	std::vector<uint8_t> jpeg;
	uint64_t sequence = 0;   // 1.. per stage, rising
	uint64_t captureNs = 0;  // CLOCK_MONOTONIC capture time of the frame
	int width = 0, height = 0;
};

} // namespace depthkey
