#include "daemon/stage_dumps.hpp"

#include "algo/pipeline_stages.hpp"
#include "daemon/log.hpp"
#include "hal/preview/snapshot_writer.hpp"

#include <cerrno>
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

int StageDumps::writeSnapshot(const DepthFrame *newestDepth, const PipelineView &view, std::string &message)
{
	if (snapshotDir_.empty()) {
		message = "snapshot not written: daemon.snapshot_dir is not set (set it in the config, on the box "
			  "under /var/lib/depthkey, where the service may write, and reload)";
		logger().warning(message);
		return -ENOENT;
	}
	const int ret = writeStages(snapshotDir_, "", newestDepth, view, &message);
	if (ret >= 0) {
		message = "snapshot written to " + snapshotDir_ + "/ (" + message + ")";
		logger().info(message, { { "SNAPSHOT_DIR", snapshotDir_ } });
	}
	return ret < 0 ? ret : 0;
}

int StageDumps::writeStages(const std::string &dir, const std::string &prefix, const DepthFrame *depth,
			    const PipelineView &view, std::string *message)
{
	static const DepthFrame kNoDepth;
	StageImages collected, stages;
	collectPipelineStages(colourLatest_, depth ? *depth : kNoDepth, view.pipeline, view.output, view.mapping,
			      collected);
	// The composite the recorder got in place of the pipeline's, and the
	// board's picture beside it.
	for (const StageImage &stage : collected.items()) {
		if (stage.name == "composite" && view.recordedComposite && !view.recordedComposite->empty())
			continue;
		if (stage.rgb)
			stages.add(stage.name, *stage.rgb);
		else if (stage.depth)
			stages.addDepth(stage.name, *stage.depth);
		else if (stage.gray)
			stages.add(stage.name, stage.kind, *stage.gray);
	}
	if (view.recordedComposite && !view.recordedComposite->empty())
		stages.add("composite", *view.recordedComposite);
	if (view.board && !view.board->empty())
		stages.add("board", *view.board);
	std::string error;
	int ret = writeStageImages(dir, prefix, stages, error);
	if (ret < 0) {
		logger().error("stage images failed: " + error, { { "SNAPSHOT_DIR", dir } });
		if (message)
			*message = "stage images failed: " + error;
		return ret;
	}
	if (message) {
		message->clear();
		for (const StageImage &stage : stages.items())
			if ((stage.rgb && !stage.rgb->empty()) || (stage.depth && !stage.depth->empty()) ||
			    (stage.gray && !stage.gray->empty()))
				*message += (message->empty() ? "" : ", ") + prefix + stage.name + ".png";
	}
	return ret;
}

} // namespace depthkey
