// hal/depthkey_shm.h as a consumer compiles it: tests/consumer/shm_reader.c
// built with gcc -std=c99 -pedantic (no feature macros) and g++ -std=c++17,
// warnings as errors, then run against a ShmRingWriter: it reads the frame
// that was written and is counted as a reader while it runs. And the header
// alone under cc -std=c99 -pedantic with _POSIX_C_SOURCE (ShmRing's check).
#include "hal/shm_ring_writer.hpp"
#include "tests/process/shell_command.hpp"
#include "tests/shm_test_util.hpp"
#include "tests/test_paths.hpp"

#include <gtest/gtest.h>

#include <csignal>
#include <cstdio>
#include <ctime>
#include <string>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

using namespace depthkey;
using depthkey::test::ShmName;

namespace {

uint64_t monotonicNs()
{
	timespec ts{};
	clock_gettime(CLOCK_MONOTONIC, &ts);
	return static_cast<uint64_t>(ts.tv_sec) * 1'000'000'000u + static_cast<uint64_t>(ts.tv_nsec);
}

struct Consumer {
	const char *compiler;
	const char *flags;
};

class ShmConsumer : public ::testing::TestWithParam<Consumer>
{
};

} // namespace

TEST_P(ShmConsumer, CompilesWithoutWarningsReadsAndIsCounted)
{
	const Consumer consumer = GetParam();
	const std::string exe = "/tmp/depthkey-consumer-" + std::to_string(getpid()) + "-" + consumer.compiler;
	int status = -1;
	std::string out = depthkey::test::run(std::string(consumer.compiler) + " " + consumer.flags +
						      " -Wall -Wextra -pedantic -Werror -I" +
						      depthkey::test::sourceDir() + " " +
						      depthkey::test::sourceDir() +
						      "/tests/consumer/shm_reader.c -o " + exe,
					      status);
	ASSERT_EQ(status, 0) << consumer.compiler << " " << consumer.flags << ":\n" << out;

	ShmName name;
	ShmRingWriter writer;
	ASSERT_EQ(writer.open(name.str(), 5, 2, DK_SHM_FORMAT_RGB24, 2, ""), 0);
	std::vector<uint8_t> pixels(5 * 2 * 3);
	unsigned long sum = 0;
	for (size_t i = 0; i < pixels.size(); i++)
		sum += pixels[i] = static_cast<uint8_t>(i * 11);
	ASSERT_EQ(writer.write(pixels.data(), 15, 123, 0), 0);
	ASSERT_EQ(writer.write(pixels.data(), 15, 124, 0), 0);

	// stdin is a pipe we hold: the reader stays until we close it.
	int toChild[2], fromChild[2];
	ASSERT_EQ(pipe(toChild), 0);
	ASSERT_EQ(pipe(fromChild), 0);
	pid_t child = fork();
	ASSERT_GE(child, 0);
	if (child == 0) {
		dup2(toChild[0], STDIN_FILENO);
		dup2(fromChild[1], STDOUT_FILENO);
		close(toChild[1]);
		close(fromChild[0]);
		execl(exe.c_str(), exe.c_str(), name.c_str(), nullptr);
		_exit(127);
	}
	close(toChild[0]);
	close(fromChild[1]);
	FILE *lines = fdopen(fromChild[0], "r");
	char line[256] = "";
	bool gotLine = std::fgets(line, sizeof(line), lines) != nullptr;
	int present = writer.countReaders(monotonicNs());
	close(toChild[1]); // EOF: the reader closes and exits
	waitpid(child, &status, 0);
	std::fclose(lines);
	unlink(exe.c_str());

	ASSERT_TRUE(gotLine) << "the reader printed nothing";
	EXPECT_EQ(std::string(line), "frame 2 bytes 30 sum " + std::to_string(sum) + " presence 0\n");
	EXPECT_EQ(present, 1) << "the running reader was not counted";
	EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
	EXPECT_EQ(writer.countReaders(monotonicNs()), 0) << "a closed reader still counted";
}

INSTANTIATE_TEST_SUITE_P(Languages, ShmConsumer,
			 ::testing::Values(Consumer{ "gcc", "-std=c99" }, Consumer{ "g++", "-std=c++17 -x c++" }),
			 [](const ::testing::TestParamInfo<Consumer> &info) {
				 return std::string(info.param.compiler) == "gcc" ? "StrictC99" : "Cxx17";
			 });

// The reader header is for consumers written in C: it must build as C99.
TEST(ShmRing, ReaderHeaderCompilesAsC99)
{
	if (system("command -v cc >/dev/null 2>&1") != 0)
		GTEST_SKIP() << "no C compiler";
	const std::string src = "/tmp/depthkey-shm-c99-" + std::to_string(getpid()) + ".c";
	FILE *f = fopen(src.c_str(), "w");
	ASSERT_NE(f, nullptr);
	fputs("#include \"hal/depthkey_shm.h\"\n"
	      "int main(void) { struct dk_shm_reader r; char b[4];\n"
	      "  if (dk_shm_open(\"/x\", &r)) return 1;\n"
	      "  return dk_shm_read_latest(&r, b, sizeof(b), NULL); }\n", f);
	fclose(f);
	const std::string cmd = "cc -std=c99 -D_POSIX_C_SOURCE=200809L -pedantic -Wall -Wextra "
				"-Werror -fsyntax-only -I. " + src;
	EXPECT_EQ(system(cmd.c_str()), 0) << cmd;
	unlink(src.c_str());
}
