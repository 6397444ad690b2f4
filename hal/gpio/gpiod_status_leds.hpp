// Status LEDs on GPIO lines through libgpiod 1.6's C++ binding. A thin
// writer: the legend is ledPatternsFor(), this only requests the lines and
// writes each level when it changes, on a 125 ms event-loop timer. The C++
// binding throws; every call is wrapped here and becomes a negative errno.
// A line that fails is released and reported once through onFault; the
// other LEDs and the daemon go on. Twice a second the missing lines are
// requested again (the chip opened afresh when none is held: a chip that
// went away and came back is a new device), silently while they still fail;
// one that is back is reported through onFault with error 0. So a chip that
// returns, or a line another process let go, lights again by itself.
// A line that fails because its chip went (a USB GPIO expander unplugged)
// takes every line down with it: the others are gone too, though a steady
// one would only fail when next written, and while the daemon held them the
// old chip could not be let go and looked up afresh.
#pragma once

#include "hal/gpio/led_patterns.hpp"
#include "hal/status_leds.hpp"

#include <functional>
#include <memory>
#include <string>

namespace gpiod {
class chip;
class line;
} // namespace gpiod

namespace depthkey {

class GpiodStatusLeds : public StatusLeds
{
public:
	// Called once per failed line (and once if the chip cannot be opened):
	// the LED's name ("" for the chip), the negative errno and what failed;
	// and once more with error 0 when it works again.
	using FaultHandler = std::function<void(const std::string &led, int error,
						const std::string &detail)>;

	explicit GpiodStatusLeds(FaultHandler onFault);
	~GpiodStatusLeds() override;

	int open(EventLoop &loop, const LedSettings &settings) override;
	void show(const StatusSummary &summary) override;
	void close() override;

	int linesInUse() const;

private:
	int openChip(std::string &why);
	int requestLine(size_t led);
	void retryMissing();
	void tick();
	void release(size_t led, int error, const std::string &what);
	void letGo(size_t led);
	bool chipGone() const;
	void dropChip(int error, const std::string &what);

	FaultHandler onFault_;
	std::unique_ptr<gpiod::chip> chip_;
	std::array<std::unique_ptr<gpiod::line>, kStatusLedCount> lines_;
	std::array<int, kStatusLedCount> written_{}; // -1 = unknown
	std::array<bool, kStatusLedCount> reported_{}; // its fault reported, not yet back
	bool chipReported_ = false;
	LedSettings settings_;
	LedPatterns patterns_{};
	EventSource timer_;
	EventLoop *loop_ = nullptr;
	unsigned tick_ = 0;
	uint64_t lastRetryUs_ = 0;
};

} // namespace depthkey
