// The daemon's side of the status LEDs: the backend [leds] names, opened
// again when a reload changes [leds], shown the daemon's summary. LEDs fail
// softly: a backend that cannot open is logged once and the daemon runs on.
#pragma once

#include "hal/event_loop.hpp"
#include "hal/status_leds.hpp"
#include "settings/settings.hpp"

#include <functional>
#include <memory>

namespace depthkey {

class StatusLights
{
public:
	using LedsFactory = std::function<std::unique_ptr<StatusLeds>(const Settings &)>;
	explicit StatusLights(LedsFactory makeLeds) : makeLeds_(std::move(makeLeds)) {}

	void open(EventLoop &loop, const Settings &settings);
	// After a reload: a new backend when [leds] changed.
	void apply(EventLoop &loop, const Settings &previous, const Settings &next);
	void show(const StatusSummary &summary);
	void close();

private:
	LedsFactory makeLeds_;
	std::unique_ptr<StatusLeds> leds_;
};

} // namespace depthkey
