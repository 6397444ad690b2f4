// Runs a command line as a user or a script would, for tests of the tools
// and scripts (stdout with stderr after it, and the exit status).
#pragma once

#include <cstdio>
#include <string>
#include <sys/wait.h>

namespace depthkey::test {

// Runs command with sh; returns its stdout and stderr and sets the exit
// status (-1 when it could not run or did not exit).
inline std::string run(const std::string &command, int &status)
{
	std::string out;
	FILE *pipe = popen((command + " 2>&1").c_str(), "r");
	if (!pipe) {
		status = -1;
		return out;
	}
	char buf[512];
	while (std::fgets(buf, sizeof(buf), pipe))
		out += buf;
	int raw = pclose(pipe);
	status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
	return out;
}

// The last non-empty line of text (a tool's summary line).
inline std::string lastLine(const std::string &text)
{
	size_t end = text.find_last_not_of('\n');
	if (end == std::string::npos)
		return std::string();
	size_t start = text.rfind('\n', end);
	start = start == std::string::npos ? 0 : start + 1;
	return text.substr(start, end - start + 1);
}

} // namespace depthkey::test
