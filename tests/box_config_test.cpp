// The installed /etc/depthkey/depthkey.toml (issue 30): `make install` makes
// it from config/depthkey.toml with packaging/box-config.sed. It must load,
// name the real devices, and differ from make run's config in nothing but
// those three backend keys, so that the two cannot drift apart.
#include "config/config_loader.hpp"
#include "config/text_file.hpp"
#include "tests/test_paths.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

namespace depthkey {
namespace {

std::string boxConfig()
{
	std::string command = "sed -f " + test::sourceDir() + "/packaging/box-config.sed " + test::sourceDir() +
			      "/config/depthkey.toml";
	FILE *pipe = popen(command.c_str(), "r");
	std::string text;
	if (!pipe)
		return text;
	char buf[4096];
	size_t n;
	while ((n = fread(buf, 1, sizeof(buf), pipe)) > 0)
		text.append(buf, n);
	EXPECT_EQ(pclose(pipe), 0) << command;
	return text;
}

std::vector<std::string> lines(const std::string &text)
{
	std::vector<std::string> out;
	std::istringstream in(text);
	for (std::string line; std::getline(in, line);)
		out.push_back(line);
	return out;
}

TEST(BoxConfig, NamesTheRealDevicesAndLoads)
{
	ConfigResult result = parseConfig(boxConfig(), "box-config");
	ASSERT_TRUE(result.ok()) << (result.errors.empty() ? "" : result.errors.front().toString());
	EXPECT_EQ(result.settings.colour.backend, "v4l2");
	EXPECT_EQ(result.settings.depth.backend, "sr2");
	EXPECT_EQ(result.settings.board.backend, "colour");
	// make run's stays on the simulator.
	ConfigResult dev = loadConfig(test::sourceDir() + "/config/depthkey.toml");
	ASSERT_TRUE(dev.ok());
	EXPECT_EQ(dev.settings.colour.backend, "sim");
	EXPECT_EQ(dev.settings.depth.backend, "sim");
	EXPECT_EQ(dev.settings.board.backend, "sim");
}

TEST(BoxConfig, DiffersFromMakeRunsOnlyInTheThreeBackends)
{
	std::string source, why;
	ASSERT_EQ(readTextFile(test::sourceDir() + "/config/depthkey.toml", 1 << 20, source, why), 0) << why;
	std::vector<std::string> dev = lines(source), box = lines(boxConfig());
	ASSERT_EQ(dev.size(), box.size());
	std::vector<std::string> changed; // "[section] line"
	std::string section;
	for (size_t i = 0; i < dev.size(); i++) {
		if (!dev[i].empty() && dev[i][0] == '[')
			section = dev[i];
		if (dev[i] != box[i])
			changed.push_back(section + " " + dev[i] + " -> " + box[i]);
	}
	EXPECT_EQ(changed, (std::vector<std::string>{
				   "[colour] backend = \"sim\" -> backend = \"v4l2\"",
				   "[depth] backend = \"sim\" -> backend = \"sr2\"",
				   "[board] backend = \"sim\" -> backend = \"colour\"",
			   }));
}

} // namespace
} // namespace depthkey
