// Issue 31: the shared-memory names --check-config (and a reload) accepts
// are exactly those the daemon's writer can create (hal/shm_name.hpp).
#include "config/config_loader.hpp"
#include "hal/depthkey_shm.h"
#include "hal/shm_name.hpp"
#include "hal/shm_ring_writer.hpp"

#include <gtest/gtest.h>

#include <unistd.h>

using namespace depthkey;

namespace {

const std::string kFile = "test.toml";

ConfigError firstError(const std::string &text)
{
	ConfigResult result = parseConfig(text, kFile);
	EXPECT_EQ(result.errors.size(), 1u) << text;
	return result.errors.empty() ? ConfigError{} : result.errors[0];
}

} // namespace

// Issue 31: every name --check-config passes is one the daemon can create,
// and the names the red team found are refused with the key and the line.
TEST(ConfigLoader, SharedMemoryNamesTheDaemonCannotCreateAreRefused)
{
	// The longest name leaves room for its presence object's ".readers".
	const std::string longest = "/" + std::string(kMaxShmNameLength - 1, 'a');
	for (const std::string &bad : { std::string("/."), std::string("/.."), longest + "a", "/" + std::string(254, 'a'),
					std::string("/a\\nb"), std::string("/a\\\\b"), std::string("/caf\u00e9"),
					std::string("/a b"), std::string("/a:b") }) {
		const ConfigError e = firstError("[output]\ncomposite_name = \"" + bad + "\"\n");
		EXPECT_EQ(e.key, "output.composite_name") << bad;
		EXPECT_EQ(e.line, 2) << bad;
	}
	EXPECT_NE(firstError("[output]\nlecturer_name = \"" + longest + "a\"\n").message.find("246"),
		  std::string::npos);
	// And every accepted name is created by the writer, then removed.
	const std::string tag = std::to_string(getpid());
	for (const std::string &good : { longest.substr(0, kMaxShmNameLength - tag.size()) + tag, "/dk_" + tag + ".room-12",
					 "/." + tag }) {
		ConfigResult r = parseConfig("[output]\ncomposite_name = \"" + good + "\"\n", kFile);
		ASSERT_TRUE(r.ok()) << good;
		ShmRingWriter writer;
		ASSERT_EQ(writer.open(good, 16, 16, DK_SHM_FORMAT_RGB24, 2, ""), 0) << writer.describeError();
		EXPECT_EQ(writer.unlink(), 0);
	}
	ShmRingWriter writer;
	EXPECT_EQ(writer.open("/..", 16, 16, DK_SHM_FORMAT_RGB24, 2, ""), -EINVAL);
}
