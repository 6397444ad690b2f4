#include "daemon/stage_dumps.hpp"

#include "algo/pipeline_stages.hpp"
#include "daemon/log.hpp"
#include "hal/preview/snapshot_writer.hpp"

#include <cstdio>

namespace depthkey {

namespace {

// --preview: stage images of this many keyed frames, this many frames apart
// (2 s at 25 fps).
constexpr int kPreviewCount = 3;
constexpr uint64_t kPreviewEveryFrames = 50;

} // namespace

void StageDumps::setFolders(const std::string &snapshotDir, const std::string &previewDir)
{
	snapshotDir_ = snapshotDir;
	previewDir_ = previewDir;
}

void StageDumps::onKeyedFrame(const ColourFrame &frame, const DepthFrame *depth, uint64_t frameNumber,
			      const PipelineView &view)
{
	if (snapshotDir_.size() || previewDir_.size())
		colourLatest_ = frame;
	if (!depth || previewDir_.empty() || previewsWritten_ >= kPreviewCount)
		return;
	if (previewsWritten_ > 0 && frameNumber < lastPreviewFrame_ + kPreviewEveryFrames)
		return;
	char prefix[32];
	std::snprintf(prefix, sizeof(prefix), "frame%06llu-", static_cast<unsigned long long>(frameNumber));
	previewsWritten_++;
	lastPreviewFrame_ = frameNumber;
	if (writeStages(previewDir_, prefix, depth, view) >= 0)
		logger().info(std::string("stage preview written: ") + previewDir_ + "/" + prefix + "*.png",
			      { { "SNAPSHOT_DIR", previewDir_ } });
}

bool StageDumps::readsStages() const
{
	return !snapshotDir_.empty() || (!previewDir_.empty() && previewsWritten_ < kPreviewCount);
}

void StageDumps::writeSnapshot(const DepthFrame *newestDepth, const PipelineView &view)
{
	if (snapshotDir_.empty()) {
		logger().warning("snapshot requested but daemon.snapshot_dir is not set");
		return;
	}
	if (writeStages(snapshotDir_, "", newestDepth, view) >= 0)
		logger().info("snapshot written to " + snapshotDir_, { { "SNAPSHOT_DIR", snapshotDir_ } });
}

int StageDumps::writeStages(const std::string &dir, const std::string &prefix, const DepthFrame *depth,
			    const PipelineView &view)
{
	static const DepthFrame kNoDepth;
	StageImages stages;
	collectPipelineStages(colourLatest_, depth ? *depth : kNoDepth, view.pipeline, view.output, view.mapping,
			      stages);
	std::string error;
	int ret = writeStageImages(dir, prefix, stages, error);
	if (ret < 0)
		logger().error("stage images failed: " + error, { { "SNAPSHOT_DIR", dir } });
	return ret;
}

} // namespace depthkey
