// The pipeline's stage images written as PNGs by the daemon
// (hal/preview/snapshot_writer.hpp): a snapshot on SIGUSR1 into
// daemon.snapshot_dir, and with --preview DIR the first keyed frame and a
// few more, each as frameNNNNNN-<stage>.png, so a technician sees the stages
// without a signal. Failures are logged; the daemon runs on.
#pragma once

#include "algo/frames.hpp"
#include "algo/mapping_model.hpp"
#include "algo/pipeline.hpp"

#include <cstdint>
#include <string>

namespace depthkey {

// What the stages are drawn from: the daemon's pipeline, its last output
// and the mapping in force, borrowed for one call; and what the recorder
// got (issue 30: composite.png was the pipeline's camera-geometry image
// over the flat board.colour while the recorder got the board's geometry).
struct PipelineView {
	const Pipeline &pipeline;
	const PipelineOutput &output;
	const MappingModel &mapping;
	const RgbImage *recordedComposite = nullptr; // null: the pipeline's composite
	const RgbImage *board = nullptr;             // the board's picture; null or empty: none written
};

class StageDumps
{
public:
	// snapshotDir: daemon.snapshot_dir ("" = SIGUSR1 writes nothing);
	// previewDir: --preview ("" = none). Again on every reload.
	void setFolders(const std::string &snapshotDir, const std::string &previewDir);

	// After a keyed frame (depth null when it went out without depth):
	// keeps the colour frame for a later snapshot, and writes the preview's
	// frames when due. The stages are this frame's: process() has run.
	void onKeyedFrame(const ColourFrame &frame, const DepthFrame *depth, uint64_t frameNumber,
			  const PipelineView &view);
	// SIGUSR1 and the preview's button: the stages of the last keyed frame
	// with the newest depth. Returns 0 or a negative errno (-ENOENT: no
	// daemon.snapshot_dir), with message saying where they went or why not.
	int writeSnapshot(const DepthFrame *newestDepth, const PipelineView &view, std::string &message);
	// Whether stages may still be written from the frames to come (a
	// folder is set and, for --preview, not all written yet).
	bool readsStages() const;

private:
	// message: the files written, or the error.
	int writeStages(const std::string &dir, const std::string &prefix, const DepthFrame *depth,
			const PipelineView &view, std::string *message = nullptr);

	std::string snapshotDir_, previewDir_;
	ColourFrame colourLatest_; // kept only while a folder is set
	int previewsWritten_ = 0;
	uint64_t lastPreviewFrame_ = 0;
};

} // namespace depthkey
