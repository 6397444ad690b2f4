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
	// a watcher this is five atomic loads.
	void offer(const ColourFrame *colour, const DepthFrame *depth, const Gray8Image *seeds,
		   const PipelineOutput &output, uint64_t captureNs, uint64_t nowNs);
	void setStatus(const PreviewStatus &status);
	// Whether offer() at nowNs would take the composite: somebody watches it.
	bool wantsComposite(uint64_t nowNs) const
	{
		return encoder_.running() && encoder_.wanted(PreviewStage::Composite, nowNs);
	}

private:
	void rereadPasswords();

	PreviewSettings settings_;
	bool applied_ = false;
	PreviewEncoder encoder_;
	PreviewServer server_;
};

} // namespace depthkey
