#include "hal/gpio/gpiod_status_leds.hpp"

#include <cerrno>
#include <gpiod.hpp>
#include <system_error>

namespace depthkey {

namespace {

// Missing lines are retried twice a second, by the clock: a busy loop runs
// the LED timer late (each late tick moves the schedule), and counting ticks
// made "once a second" several seconds on a slow machine (the HIL VM under
// load took 8-11 s to take a returned chip back). Once a second gave 2.07 s
// in the campaign from a chip's return (the retry's phase plus a late loop);
// a lookup is a few opens and ioctls, and runs only while a line is missing.
constexpr uint64_t kLedRetryUs = 500000;

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

namespace {

int lineOffset(const LedSettings &s, size_t led)
{
	const int offsets[kStatusLedCount] = { s.powerLine,  s.depthLine, s.colourLine, s.calibrationLine,
					       s.readerLine, s.errorLine, s.boardLine };
	return offsets[led];
}

} // namespace

int GpiodStatusLeds::open(EventLoop &loop, const LedSettings &settings)
{
	close();
	settings_ = settings;
	reported_.fill(false);
	chipReported_ = false;
	patterns_ = ledPatternsFor(StatusSummary{});
	tick_ = 0;
	loop_ = &loop;
	lastRetryUs_ = loop.nowUs();
	std::string why;
	int r = openChip(why);
	if (r < 0 && onFault_) {
		chipReported_ = true;
		onFault_("", r, why);
	}
	// A line that fails is reported by requestLine() and retried by tick().
	for (size_t i = 0; r == 0 && i < kStatusLedCount; i++)
		if (lineOffset(settings_, i) >= 0)
			requestLine(i);
	// The timer also runs without a chip: it retries once a second.
	int t = loop.addPeriodic(kLedTickUs, [this] { tick(); }, timer_);
	return r < 0 ? r : t;
}

int GpiodStatusLeds::openChip(std::string &why)
{
	try {
		chip_ = std::make_unique<gpiod::chip>(settings_.chip, gpiod::chip::OPEN_LOOKUP);
	} catch (const std::exception &e) {
		chip_.reset();
		why = "cannot open GPIO chip " + settings_.chip + ": " + e.what();
		return errnoOf(e);
	}
	if (!*chip_) {
		chip_.reset();
		why = "no GPIO chip " + settings_.chip;
		return -ENODEV;
	}
	return 0;
}

// Requests one LED's line; on failure releases it and reports the fault
// (once: not again while it stays reported).
int GpiodStatusLeds::requestLine(size_t led)
{
	const int offset = lineOffset(settings_, led);
	gpiod::line_request request{ "depthkeyd", gpiod::line_request::DIRECTION_OUTPUT,
				     settings_.activeLow ? gpiod::line_request::FLAG_ACTIVE_LOW : std::bitset<32>() };
	try {
		auto line = std::make_unique<gpiod::line>(chip_->get_line(static_cast<unsigned>(offset)));
		line->request(request, 0);
		lines_[led] = std::move(line);
		written_[led] = -1; // the next tick writes its level
		return 0;
	} catch (const std::exception &e) {
		if (!reported_[led])
			release(led, errnoOf(e), "cannot request line " + std::to_string(offset) + " of " + settings_.chip +
							 ": " + e.what());
		else
			lines_[led].reset();
		return errnoOf(e);
	}
}

// Once a second while a line is missing: the chip again if none is held,
// then the missing lines. Failures stay quiet (reported already).
void GpiodStatusLeds::retryMissing()
{
	bool missing = false;
	for (size_t i = 0; i < kStatusLedCount; i++)
		missing |= lineOffset(settings_, i) >= 0 && !lines_[i];
	if (!missing && chip_)
		return;
	if (linesInUse() == 0)
		chip_.reset();
	if (!chip_) {
		std::string why;
		if (openChip(why) < 0)
			return;
		if (chipReported_ && onFault_)
			onFault_("", 0, "GPIO chip " + settings_.chip + " is back");
		chipReported_ = false;
	}
	for (size_t i = 0; i < kStatusLedCount; i++) {
		if (lineOffset(settings_, i) < 0 || lines_[i] || requestLine(i) < 0)
			continue;
		if (reported_[i] && onFault_)
			onFault_(statusLedName(static_cast<StatusLed>(i)), 0,
				 "line " + std::to_string(lineOffset(settings_, i)) + " of " + settings_.chip + " is back");
		reported_[i] = false;
	}
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
	const uint64_t now = loop_->nowUs();
	if (now - lastRetryUs_ >= kLedRetryUs) {
		lastRetryUs_ = now;
		retryMissing();
	}
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
			if (chipGone()) {
				dropChip(errnoOf(e), std::string("cannot set line: ") + e.what());
				break;
			}
			release(i, errnoOf(e), std::string("cannot set line: ") + e.what());
		}
	}
	tick_ = (tick_ + 1) % kLedTicksPerCycle;
}

// Whether the chip still answers: a line's info asked of it (an ioctl on
// the chip's fd, ENODEV once the kernel removed the chip).
bool GpiodStatusLeds::chipGone() const
{
	if (!chip_)
		return true;
	try {
		chip_->get_line(0).update();
		return false;
	} catch (const std::exception &) {
		return true;
	}
}

// Lets go of every line and of the chip, reported once as the chip's fault;
// retryMissing() looks the chip up afresh twice a second, and its return is
// reported as the chip's (the lines' own faults were not reported, so they
// come back quietly with it).
void GpiodStatusLeds::dropChip(int error, const std::string &what)
{
	for (size_t i = 0; i < kStatusLedCount; i++) {
		letGo(i);
		written_[i] = -1;
		reported_[i] = false;
	}
	chip_.reset();
	if (!chipReported_ && onFault_)
		onFault_("", error, "GPIO chip " + settings_.chip + " is gone: " + what);
	chipReported_ = true;
}

// Releases one line's handle, if held.
void GpiodStatusLeds::letGo(size_t led)
{
	if (!lines_[led])
		return;
	try {
		lines_[led]->release();
	} catch (const std::exception &) {
		// Already gone with its chip; dropping our handle is all that is left.
	}
	lines_[led].reset();
}

void GpiodStatusLeds::release(size_t led, int error, const std::string &what)
{
	letGo(led);
	if (!reported_[led] && onFault_)
		onFault_(statusLedName(static_cast<StatusLed>(led)), error, what);
	reported_[led] = true;
}

} // namespace depthkey
