// Status LEDs: what the technician reads on the box. The daemon hands over a
// summary of its state; a backend turns it into lines and blink patterns.
// LEDs fail softly: a backend that loses a line goes on without it.
#pragma once

#include "hal/event_loop.hpp"
#include "settings/settings.hpp"

#include <memory>

namespace depthkey {

struct StatusSummary {
	bool colourOk = false;
	bool depthOk = false;
	bool calibrated = false;
	bool readerAttached = false; // a recorder reads the shared memory (when known)
	bool error = false;     // a persistent error is being reported
	bool boardOk = true;    // the board source delivers (false: lost, last picture kept)
	bool boardCalibrated = true; // the composite is in the board's geometry
	bool operator==(const StatusSummary &) const = default;
};

class StatusLeds
{
public:
	virtual ~StatusLeds() = default;
	virtual int open(EventLoop &loop, const LedSettings &settings) = 0;
	virtual void show(const StatusSummary &summary) = 0;
	virtual void close() = 0;
};

// For boxes without LEDs (backend "none").
class NoStatusLeds : public StatusLeds
{
public:
	int open(EventLoop &, const LedSettings &) override { return 0; }
	void show(const StatusSummary &) override {}
	void close() override {}
};

} // namespace depthkey
