#include "daemon/status_lights.hpp"

#include "daemon/log.hpp"

namespace depthkey {

void StatusLights::open(EventLoop &loop, const Settings &settings)
{
	leds_ = makeLeds_(settings);
	if (leds_->open(loop, settings.leds) < 0)
		logger().errorOnce("leds", "status LEDs unavailable, running without them",
				   { { "DEVICE", "leds" } });
}

void StatusLights::apply(EventLoop &loop, const Settings &previous, const Settings &next)
{
	if (previous.leds == next.leds)
		return;
	leds_->close();
	leds_ = makeLeds_(next);
	leds_->open(loop, next.leds);
}

void StatusLights::show(const StatusSummary &summary)
{
	if (leds_)
		leds_->show(summary);
}

void StatusLights::close()
{
	if (leds_)
		leds_->close();
}

} // namespace depthkey
