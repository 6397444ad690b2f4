// SIGHUP: the config read again, then the calibration and board image it
// names. Reading and parsing run on a worker thread (hal/
// background_job.hpp): a hostile 1 MiB file takes longer to parse than
// several frame periods. The loop thread only applies the result; a config
// that is refused is logged with its file and line and the previous one
// kept. A SIGHUP during a reload is folded into one more reload after it.
// READY=1 is withdrawn meanwhile (StatusReporter::reloading).
#pragma once

#include "config/config_loader.hpp"
#include "hal/background_job.hpp"
#include "daemon/command_line_overrides.hpp"
#include "daemon/status_reporter.hpp"
#include "hal/event_loop.hpp"
#include "settings/settings.hpp"
#include "wiring/pipeline_setup.hpp"

#include <functional>
#include <string>

namespace depthkey {

class ConfigReloader
{
public:
	// Called on the loop thread with a config that loaded, the overrides
	// applied, and the files it names as they were read.
	using Apply = std::function<void(const Settings &, const PipelineFiles &)>;

	ConfigReloader(EventLoop &loop, StatusReporter &status, const std::string &configPath,
		       const CommandLineOverrides &overrides, Apply apply)
		: loop_(loop), status_(status), configPath_(configPath), overrides_(overrides),
		  apply_(std::move(apply)) {}

	void reload();

private:
	// What the worker read, for the loop thread to apply.
	struct Pending {
		ConfigResult config;
		PipelineFiles files;
	};
	void finish(const Pending &next);

	EventLoop &loop_;
	StatusReporter &status_;
	const std::string &configPath_;           // the daemon's, borrowed
	const CommandLineOverrides &overrides_;
	Apply apply_;
	BackgroundJob job_;
	bool again_ = false;
};

} // namespace depthkey
