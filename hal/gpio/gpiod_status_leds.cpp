#include "hal/gpio/gpiod_status_leds.hpp"

#include <cerrno>
#include <gpiod.hpp>
#include <system_error>

namespace depthkey {

namespace {

int errnoOf(const std::exception &e)
{
	if (auto *se = dynamic_cast<const std::system_error *>(&e))
		return se->code().value() > 0 ? -se->code().value() : -EIO;
	return -EIO;
}

} // namespace

GpiodStatusLeds::GpiodStatusLeds(FaultHandler onFault) : onFault_(std::move(onFault))
{
	written_.fill(-1);
}

GpiodStatusLeds::~GpiodStatusLeds()
{
	close();
}

int GpiodStatusLeds::open(EventLoop &loop, const LedSettings &settings)
{
	close();
	try {
		chip_ = std::make_unique<gpiod::chip>(settings.chip, gpiod::chip::OPEN_LOOKUP);
	} catch (const std::exception &e) {
		chip_.reset();
		if (onFault_)
			onFault_("", errnoOf(e), "cannot open GPIO chip " + settings.chip + ": " + e.what());
		return errnoOf(e);
	}
	if (!*chip_) {
		chip_.reset();
		if (onFault_)
			onFault_("", -ENODEV, "no GPIO chip " + settings.chip);
		return -ENODEV;
	}
	int offsets[kStatusLedCount] = { settings.powerLine, settings.depthLine,
					 settings.colourLine, settings.calibrationLine,
					 settings.readerLine, settings.errorLine, settings.boardLine };
	gpiod::line_request request{ "depthkeyd", gpiod::line_request::DIRECTION_OUTPUT,
				     settings.activeLow ? gpiod::line_request::FLAG_ACTIVE_LOW
							: std::bitset<32>() };
	for (size_t i = 0; i < kStatusLedCount; i++) {
		if (offsets[i] < 0)
			continue;
		try {
			auto line = std::make_unique<gpiod::line>(
				chip_->get_line(static_cast<unsigned>(offsets[i])));
			line->request(request, 0);
			lines_[i] = std::move(line);
			written_[i] = 0;
		} catch (const std::exception &e) {
			release(i, errnoOf(e), "cannot request line " + std::to_string(offsets[i]) +
						       " of " + settings.chip + ": " + e.what());
		}
	}
	patterns_ = ledPatternsFor(StatusSummary{});
	tick_ = 0;
	return loop.addPeriodic(kLedTickUs, [this] { tick(); }, timer_);
}

void GpiodStatusLeds::show(const StatusSummary &summary)
{
	patterns_ = ledPatternsFor(summary);
}

void GpiodStatusLeds::close()
{
	timer_.reset();
	for (size_t i = 0; i < kStatusLedCount; i++) {
		if (!lines_[i])
			continue;
		try {
			lines_[i]->set_value(0); // leave the box dark, not frozen lit
			lines_[i]->release();
		} catch (const std::exception &) {
			// Closing: nothing more to do for a line that is gone.
		}
		lines_[i].reset();
	}
	written_.fill(-1);
	chip_.reset();
}

int GpiodStatusLeds::linesInUse() const
{
	int n = 0;
	for (const auto &line : lines_)
		n += line != nullptr;
	return n;
}

void GpiodStatusLeds::tick()
{
	for (size_t i = 0; i < kStatusLedCount; i++) {
		if (!lines_[i])
			continue;
		int level = ledLit(patterns_[i], tick_) ? 1 : 0;
		if (level == written_[i])
			continue;
		try {
			lines_[i]->set_value(level);
			written_[i] = level;
		} catch (const std::exception &e) {
			release(i, errnoOf(e), std::string("cannot set line: ") + e.what());
		}
	}
	tick_ = (tick_ + 1) % kLedTicksPerCycle;
}

void GpiodStatusLeds::release(size_t led, int error, const std::string &what)
{
	if (lines_[led]) {
		try {
			lines_[led]->release();
		} catch (const std::exception &) {
			// Already gone with its chip; dropping our handle is all that is left.
		}
		lines_[led].reset();
	}
	if (onFault_)
		onFault_(statusLedName(static_cast<StatusLed>(led)), error, what);
}

} // namespace depthkey
