// Logging for depthkeyd: structured journal entries (MESSAGE plus DEVICE=,
// FRAME=, ERROR=, ... fields) when stderr is the journal or the daemon runs
// under systemd, plain "level: message (field=value ...)" lines on stderr
// otherwise. A repeated error is logged once, and again only when it changes.
#pragma once

#include "daemon/recent_errors.hpp"

#include <cstdint>
#include <initializer_list>
#include <map>
#include <string>
#include <string_view>

namespace depthkey {

enum class LogLevel { Error = 3, Warning = 4, Info = 6, Debug = 7 };

// Parses "error" | "warning" | "info" | "debug"; false for anything else.
bool parseLogLevel(std::string_view text, LogLevel &level);

struct LogField {
	const char *name;   // journal field name, upper case: DEVICE, FRAME, ERROR
	std::string value;
};

class Logger
{
public:
	// Decides journal vs stderr from JOURNAL_STREAM (set by systemd for the
	// service's stderr); DEPTHKEY_LOG=stderr|journal overrides for tests.
	Logger();

	void setLevel(LogLevel level) { level_ = level; }
	bool toJournal() const { return journal_; }

	void log(LogLevel level, std::string_view message, std::initializer_list<LogField> fields = {});
	void error(std::string_view m, std::initializer_list<LogField> f = {}) { log(LogLevel::Error, m, f); }
	void warning(std::string_view m, std::initializer_list<LogField> f = {}) { log(LogLevel::Warning, m, f); }
	void info(std::string_view m, std::initializer_list<LogField> f = {}) { log(LogLevel::Info, m, f); }
	void debug(std::string_view m, std::initializer_list<LogField> f = {}) { log(LogLevel::Debug, m, f); }

	// A persistent condition identified by key (e.g. "colour-camera"): logged
	// when first seen and whenever its message changes; repeats are counted.
	void errorOnce(const std::string &key, std::string_view message,
		       std::initializer_list<LogField> fields = {});
	// The condition is over: logs that it cleared (with the repeat count) if
	// it was active, so the journal shows when a device came back.
	void clearError(const std::string &key, std::string_view message,
			std::initializer_list<LogField> fields = {});
	bool errorActive(const std::string &key) const { return active_.count(key) != 0; }
	size_t activeErrorCount() const { return active_.size(); }
	// The last distinct error lines logged (the preview page shows them).
	const RecentErrors &recentErrors() const { return recent_; }

private:
	struct ActiveError {
		std::string message;
		uint64_t repeats = 0;
	};

	LogLevel level_ = LogLevel::Info;
	bool journal_ = false;
	std::map<std::string, ActiveError> active_;
	RecentErrors recent_;
};

// The daemon's logger (one process, one log).
Logger &logger();

std::string errnoText(int negativeErrno); // "-19 (No such device)"

} // namespace depthkey
