// Where tests find the binaries and files of the tree they were built from.
#pragma once

#include <string>
#include <unistd.h>

namespace depthkey::test {

// build/bin (or build/san/bin): the folder holding this test binary.
inline std::string binDir()
{
	char buf[4096];
	ssize_t n = readlink("/proc/self/exe", buf, sizeof(buf) - 1);
	if (n <= 0)
		return "build/bin";
	std::string path(buf, static_cast<size_t>(n));
	return path.substr(0, path.rfind('/'));
}

// The source tree: tests run from the top of the repository (make test).
inline std::string sourceDir()
{
	char buf[4096];
	return getcwd(buf, sizeof(buf)) ? std::string(buf) : std::string(".");
}

} // namespace depthkey::test
