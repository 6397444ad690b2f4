#include "daemon/config_reloader.hpp"

#include "daemon/log.hpp"

#include <memory>

namespace depthkey {

void ConfigReloader::reload()
{
	if (job_.running()) {
		again_ = true;
		return;
	}
	status_.reloading();
	auto next = std::make_shared<Pending>();
	int ret = job_.start(
		loop_,
		[next, path = configPath_, overrides = overrides_] {
			next->config = loadConfig(path);
			if (next->config.ok()) {
				overrides.applyTo(next->config.settings);
				next->files = loadPipelineFiles(next->config.settings);
			}
		},
		[this, next] { finish(*next); });
	if (ret < 0) {
		logger().error("config reload failed: cannot start a worker: " + errnoText(ret),
			       { { "CONFIG_FILE", configPath_ } });
		status_.reloaded();
	}
}

void ConfigReloader::finish(const Pending &next)
{
	const ConfigResult &result = next.config;
	if (!result.ok()) {
		for (const ConfigError &e : result.errors)
			logger().error("config reload refused: " + e.toString(),
				       { { "CONFIG_FILE", e.file }, { "CONFIG_LINE", std::to_string(e.line) } });
		logger().warning("keeping the previous configuration", { { "CONFIG_FILE", configPath_ } });
	} else {
		apply_(result.settings, next.files);
		logger().info("configuration reloaded", { { "CONFIG_FILE", configPath_ } });
	}
	status_.reloaded();
	if (again_) {
		again_ = false;
		reload();
	}
}

} // namespace depthkey
