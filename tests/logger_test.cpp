#include "daemon/log.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <unistd.h>

using namespace depthkey;

namespace {

// Captures what the logger writes to stderr while `body` runs.
template<typename F>
std::string captureStderr(F body)
{
	std::fflush(stderr);
	int saved = dup(STDERR_FILENO);
	FILE *tmp = std::tmpfile();
	dup2(fileno(tmp), STDERR_FILENO);
	body();
	std::fflush(stderr);
	dup2(saved, STDERR_FILENO);
	close(saved);
	std::rewind(tmp);
	std::string text;
	char buf[512];
	while (size_t n = std::fread(buf, 1, sizeof(buf), tmp))
		text.append(buf, n);
	std::fclose(tmp);
	return text;
}

int count(const std::string &text, const std::string &what)
{
	int n = 0;
	for (size_t pos = text.find(what); pos != std::string::npos; pos = text.find(what, pos + 1))
		n++;
	return n;
}

} // namespace

TEST(Logger, RepeatedErrorIsLoggedOnceThenWhenItChanges)
{
	setenv("DEPTHKEY_LOG", "stderr", 1);
	Logger log;
	std::string out = captureStderr([&] {
		for (int i = 0; i < 5; ++i)
			log.errorOnce("cam", "camera lost", { { "DEVICE", "cam0" } });
		log.errorOnce("cam", "camera stalled", { { "DEVICE", "cam0" } });
		log.errorOnce("cam", "camera stalled");
		log.clearError("cam", "camera back");
		log.clearError("cam", "camera back"); // not active any more: silent
	});
	EXPECT_EQ(count(out, "camera lost"), 1) << out;
	EXPECT_EQ(count(out, "camera stalled"), 1) << out;
	EXPECT_EQ(count(out, "camera back"), 1) << out;
	EXPECT_NE(out.find("device=cam0"), std::string::npos) << out;
	EXPECT_NE(out.find("repeated 1 times"), std::string::npos) << out;
	EXPECT_FALSE(log.errorActive("cam"));
}

TEST(Logger, LevelFiltersMessages)
{
	setenv("DEPTHKEY_LOG", "stderr", 1);
	Logger log;
	log.setLevel(LogLevel::Warning);
	std::string out = captureStderr([&] {
		log.info("chatty");
		log.warning("important");
	});
	EXPECT_EQ(out.find("chatty"), std::string::npos);
	EXPECT_NE(out.find("important"), std::string::npos);
	LogLevel level;
	EXPECT_TRUE(parseLogLevel("debug", level));
	EXPECT_EQ(level, LogLevel::Debug);
	EXPECT_FALSE(parseLogLevel("verbose", level));
}
