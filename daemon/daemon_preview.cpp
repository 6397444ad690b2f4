// What the daemon tells the preview page (/status.json, /metrics): the
// figures of the STATUS= line and the counters only the page shows.
#include "daemon/daemon.hpp"

namespace depthkey {

PreviewStatus Daemon::previewStatus(double colourFps, double depthFps, double outputFps) const
{
	PreviewStatus s;
	s.uptimeS = static_cast<double>(loop_.nowUs() - startedUs_) / 1e6;
	auto device = [this](const char *role, const auto *camera, double fps, uint64_t frames) {
		PreviewDevice d;
		d.role = role;
		if (camera) {
			DeviceStatus status = camera->status();
			d.name = camera->name();
			d.state = deviceStateName(status.state);
			d.dropped = status.droppedFrames;
			auto it = deviceCounters_.find(d.name);
			if (it != deviceCounters_.end()) {
				d.faults = it->second.faults;
				d.reconnects = it->second.reconnects;
			}
		}
		d.fps = fps;
		d.frames = frames;
		return d;
	};
	s.devices.push_back(device("colour", colour_.get(), colourFps, colourFrames_));
	s.devices.push_back(device("depth", depth_.get(), depthFps, depthFrames_));
	s.outputFps = outputFps;
	s.published = published_;
	s.paired = queue_.pairer().stats().paired;
	s.unpaired = queue_.pairer().stats().unpaired;
	s.calibrated = summary().calibrated;
	s.calibrationFile = settings_.mapping.calibrationFile;
	// The measured offset when there is one (pairing.offset_ms = "auto"
	// applies it), else how long depth frames take to arrive after their stamp.
	s.depthLatencyMs = latencyEstimate_.valid ? -latencyEstimate_.offsetMs : depthLatencyMs_;
	s.readersComposite = readers_.composite;
	s.readersLecturer = readers_.lecturer;
	s.readersBoardLecturer = readers_.boardLecturer;
	return s;
}

} // namespace depthkey
