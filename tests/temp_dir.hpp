// A fresh folder under /tmp, removed with everything in it when the test ends.
#pragma once

#include <cstdlib>
#include <filesystem>
#include <string>

namespace depthkey::test {

class TempDir
{
public:
	TempDir()
	{
		char pattern[] = "/tmp/depthkey-rec-XXXXXX";
		const char *dir = mkdtemp(pattern);
		path_ = dir ? dir : "";
	}
	~TempDir()
	{
		std::error_code ignored; // a leftover temp folder fails no test
		if (!path_.empty())
			std::filesystem::remove_all(path_, ignored);
	}
	TempDir(const TempDir &) = delete;
	TempDir &operator=(const TempDir &) = delete;
	operator std::string() const { return path_; }
	std::string operator+(const char *sub) const { return path_ + sub; }

private:
	std::string path_;
};

} // namespace depthkey::test
