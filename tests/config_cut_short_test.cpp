// Issue 31: a config written in place and cut short is refused. The shipped
// file says it ends with [end] (daemon.end_marker = true); cut anywhere
// after that key, it lacks [end], and the error names the key and the last
// line, where the file stops. A config without the key (one written before
// the check existed) is read as before.
#include "config/config_loader.hpp"
#include "tests/test_paths.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

using namespace depthkey;

namespace {

std::string shippedConfig()
{
	std::ifstream in(test::sourceDir() + "/config/depthkey.toml");
	std::stringstream text;
	text << in.rdbuf();
	return text.str();
}

// The text up to (not including) the first occurrence of what.
std::string cutBefore(const std::string &text, const std::string &what)
{
	const size_t at = text.find(what);
	EXPECT_NE(at, std::string::npos) << what;
	return text.substr(0, at);
}

int lines(const std::string &text)
{
	int n = 0;
	for (char c : text)
		n += c == '\n';
	return n + (!text.empty() && text.back() != '\n');
}

} // namespace

TEST(ConfigCutShort, TheShippedFileIsCompleteAndSaysSo)
{
	const std::string text = shippedConfig();
	ConfigResult result = parseConfig(text, "depthkey.toml");
	EXPECT_TRUE(result.ok()) << (result.errors.empty() ? "" : result.errors[0].toString());
	EXPECT_NE(text.find("\nend_marker = true\n"), std::string::npos);
	EXPECT_NE(text.find("\n[end]\n"), std::string::npos);
}

TEST(ConfigCutShort, ACutAnywhereAfterTheMarkerKeyIsRefusedAtTheLastLine)
{
	const std::string text = shippedConfig();
	// The red team's two cuts (mid-value after "max_skew_ms = 1", and
	// before [output]), the cut that loses only [end], and one every 997
	// bytes that the TOML parser accepts.
	std::vector<std::string> cuts = { cutBefore(text, "max_skew_ms = ") + "max_skew_ms = 1",
					  cutBefore(text, "\n[output]\n"), cutBefore(text, "\n[end]\n") };
	for (size_t at = text.find("end_marker = true\n") + 18; at < text.size() - 10; at += 997)
		cuts.push_back(text.substr(0, at));
	int refusedForTheEnd = 0;
	for (const std::string &cut : cuts) {
		ConfigResult result = parseConfig(cut, "depthkey.toml");
		ASSERT_FALSE(result.ok()) << "a cut at byte " << cut.size() << " was accepted";
		const ConfigError &last = result.errors.back();
		if (last.key != "end")
			continue; // cut mid-token: a syntax error says where already
		refusedForTheEnd++;
		EXPECT_EQ(last.file, "depthkey.toml");
		EXPECT_EQ(last.line, lines(cut)) << "at byte " << cut.size();
		EXPECT_NE(last.message.find("missing section [end]: the file is cut short"), std::string::npos)
			<< last.message;
	}
	EXPECT_GE(refusedForTheEnd, 3);
	// The red team's cuts are not syntax errors: the marker is all that catches them.
	for (size_t i = 0; i < 3; i++)
		EXPECT_EQ(parseConfig(cuts[i], "depthkey.toml").errors.back().key, "end") << i;
}

TEST(ConfigCutShort, ConfigsWithoutTheMarkerKeyAreReadAsBefore)
{
	EXPECT_TRUE(parseConfig("[colour]\nwidth = 320\n", "old.toml").ok());
	EXPECT_TRUE(parseConfig("[daemon]\nend_marker = false\n[colour]\nwidth = 320\n", "old.toml").ok());
	EXPECT_TRUE(parseConfig("[daemon]\nend_marker = true\n[colour]\nwidth = 320\n[end]\n", "new.toml").ok());
	// [end] is a marker, with nothing in it.
	ConfigResult withKey = parseConfig("[daemon]\nend_marker = true\n[end]\ncomplete = true\n", "x.toml");
	ASSERT_EQ(withKey.errors.size(), 1u);
	EXPECT_EQ(withKey.errors[0].key, "end.complete");
}
