// The daemon's side of the live preview: starts the JPEG worker and the HTTP
// server from [preview] (restarting them when a reload changes it), hands
// them the stages somebody watches, and the status once a second. A preview
// that cannot start is logged (DEVICE=preview) and the daemon runs on. Every
// reload re-reads the password file; one that is refused then closes the
// page (hal/preview/preview_auth.hpp says why) and is logged once.
#pragma once

#include "algo/frames.hpp"
#include "algo/pipeline.hpp"
#include "hal/preview/preview_encoder.hpp"
#include "hal/preview/preview_server.hpp"
#include "settings/settings.hpp"

namespace depthkey {

// What the recorder gets with this frame, the shared memory's own pictures
// (issue 30: the page showed the pipeline's camera-geometry composite over
// the flat board.colour while the recorder got the board's geometry).
struct RecordedPictures {
	const RgbImage *composite = nullptr;   // as published; null when made only in the shared memory
	const RgbaImage *boardLayer = nullptr; // board geometry: the warped lecturer layer; else null
	const RgbImage *board = nullptr;       // the board's picture; null or empty: a solid colour unmade
	// The composite went out, made only in the shared memory (composite
	// null): the loop makes an image of it here too once a preview client
	// asks, so the preview must hear it is made, or it answers "no frame"
	// and never asks.
	bool compositeInSharedMemory = false;
};

class PreviewFeed
{
public:
	~PreviewFeed() { stop(); }

	// Starts, restarts or keeps the server as settings say; a server that
	// cannot start is logged and tried again at the next apply. With
	// portInUse (the daemon's start), a port another process listens on is
	// not logged but returned, -EADDRINUSE with portInUse saying so: a
	// second depthkeyd started by mistake exits (issue 30).
	int apply(const PreviewSettings &settings, std::string *portInUse = nullptr);
	void stop();
	bool running() const { return server_.running(); }
	int port() const { return server_.port(); }

	// Per frame, on the event loop: copies the stages that are watched (and
	// due under the worker's frame cap). Null stages are left out. Without
	// a watcher this is seven atomic loads. In camera geometry the lecturer
	// layer is made here from the colour frame and its alpha, as the shared
	// memory makes it, only while it is watched.
	void offer(const ColourFrame *colour, const DepthFrame *depth, const Gray8Image *seeds,
		   const PipelineOutput &output, const RecordedPictures &recorded, uint64_t captureNs,
		   uint64_t nowNs);
	void setStatus(const PreviewStatus &status);
	// A snapshot asked for on the page (POST /snapshot) waits for
	// answerSnapshot(): ret 0, or a negative errno (-ENOENT: no
	// daemon.snapshot_dir), with what was written or why not.
	bool snapshotPending() { return server_.running() && server_.snapshots().pending(); }
	void answerSnapshot(int ret, const std::string &message) { server_.snapshots().answer(ret, message); }
	// Whether offer() at nowNs would take the composite: somebody watches it.
	bool wantsComposite(uint64_t nowNs) const
	{
		return encoder_.running() && encoder_.wanted(PreviewStage::Composite, nowNs);
	}
	// The same for the lecturer layer.
	bool wantsLecturer(uint64_t nowNs) const
	{
		return encoder_.running() && encoder_.wanted(PreviewStage::Lecturer, nowNs);
	}

private:
	void rereadPasswords();

	PreviewSettings settings_;
	bool applied_ = false;
	PreviewEncoder encoder_;
	PreviewServer server_;
	RgbaImage layer_; // the camera-geometry lecturer layer, reused
};

} // namespace depthkey
