#include "daemon/log.hpp"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <sys/stat.h>
#include <systemd/sd-journal.h>
#include <unistd.h>
#include <vector>

namespace depthkey {

namespace {

const char *levelName(LogLevel level)
{
	switch (level) {
	case LogLevel::Error:
		return "error";
	case LogLevel::Warning:
		return "warning";
	case LogLevel::Info:
		return "info";
	case LogLevel::Debug:
		return "debug";
	}
	return "?";
}

// systemd sets JOURNAL_STREAM=dev:inode for the stream connected to stderr;
// if stderr is still that stream, our output would land in the journal as
// unstructured text, so write structured entries instead.
bool stderrIsJournal()
{
	const char *override = std::getenv("DEPTHKEY_LOG");
	if (override)
		return std::strcmp(override, "journal") == 0;
	const char *stream = std::getenv("JOURNAL_STREAM");
	if (!stream)
		return false;
	unsigned long long dev = 0, ino = 0;
	if (std::sscanf(stream, "%llu:%llu", &dev, &ino) != 2)
		return false;
	struct stat st;
	if (fstat(STDERR_FILENO, &st) < 0)
		return false;
	return st.st_dev == dev && st.st_ino == ino;
}

} // namespace

bool parseLogLevel(std::string_view text, LogLevel &level)
{
	for (LogLevel l : { LogLevel::Error, LogLevel::Warning, LogLevel::Info, LogLevel::Debug }) {
		if (text == levelName(l)) {
			level = l;
			return true;
		}
	}
	return false;
}

Logger::Logger() : journal_(stderrIsJournal())
{
}

void Logger::log(LogLevel level, std::string_view message, std::initializer_list<LogField> fields)
{
	if (static_cast<int>(level) > static_cast<int>(level_))
		return;
	if (level == LogLevel::Error) {
		timespec now{};
		clock_gettime(CLOCK_REALTIME, &now);
		recent_.add(message, static_cast<uint64_t>(now.tv_sec) * 1'000'000'000u + static_cast<uint64_t>(now.tv_nsec));
	}

	if (journal_) {
		std::vector<std::string> entries;
		entries.reserve(fields.size() + 3);
		entries.push_back("MESSAGE=" + std::string(message));
		entries.push_back("PRIORITY=" + std::to_string(static_cast<int>(level)));
		entries.push_back("SYSLOG_IDENTIFIER=depthkeyd");
		for (const LogField &f : fields)
			entries.push_back(std::string(f.name) + "=" + f.value);
		std::vector<iovec> iov;
		for (std::string &e : entries)
			iov.push_back({ e.data(), e.size() });
		if (sd_journal_sendv(iov.data(), static_cast<int>(iov.size())) >= 0)
			return;
		// The journal socket is gone: fall through to stderr, never lose it.
	}

	std::string line = "depthkeyd: ";
	line += levelName(level);
	line += ": ";
	line += message;
	if (fields.size()) {
		line += " (";
		bool first = true;
		for (const LogField &f : fields) {
			if (!first)
				line += ' ';
			first = false;
			for (const char *c = f.name; *c; ++c)
				line += static_cast<char>(*c >= 'A' && *c <= 'Z' ? *c - 'A' + 'a' : *c);
			line += '=';
			line += f.value;
		}
		line += ')';
	}
	line += '\n';
	std::fwrite(line.data(), 1, line.size(), stderr);
}

void Logger::errorOnce(const std::string &key, std::string_view message,
		       std::initializer_list<LogField> fields)
{
	auto it = active_.find(key);
	if (it != active_.end() && it->second.message == message) {
		it->second.repeats++;
		return;
	}
	active_[key] = { std::string(message), 0 };
	log(LogLevel::Error, message, fields);
}

void Logger::clearError(const std::string &key, std::string_view message,
			std::initializer_list<LogField> fields)
{
	auto it = active_.find(key);
	if (it == active_.end())
		return;
	std::string text(message);
	if (it->second.repeats)
		text += " (the error repeated " + std::to_string(it->second.repeats) + " times)";
	active_.erase(it);
	log(LogLevel::Info, text, fields);
}

Logger &logger()
{
	static Logger instance;
	return instance;
}

std::string errnoText(int negativeErrno)
{
	return std::to_string(negativeErrno) + " (" + std::strerror(-negativeErrno) + ")";
}

} // namespace depthkey
