// GoogleTest main of both test binaries, depthkey-unit-tests (tests/*.cpp)
// and depthkey-process-tests (tests/process/*.cpp). Besides gtest's own report
// it prints one closing line "NAME: N passed, N failed, N skipped", NAME the
// binary's, so that CI can count the tests whatever runner it knows.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <utility>

namespace {

class SummaryPrinter : public testing::EmptyTestEventListener
{
public:
	explicit SummaryPrinter(std::string name) : name_(std::move(name)) {}

private:
	void OnTestProgramEnd(const testing::UnitTest &unit) override
	{
		std::printf("%s: %d passed, %d failed, %d skipped\n", name_.c_str(),
			    unit.successful_test_count(), unit.failed_test_count(),
			    unit.skipped_test_count());
		std::fflush(stdout);
	}

	std::string name_;
};

} // namespace

int main(int argc, char **argv)
{
	testing::InitGoogleTest(&argc, argv);
	// The name it was started by, without the folder: the same binary
	// reports as itself wherever it was built (build/bin, build/san/bin).
	std::string name = argc > 0 ? argv[0] : "depthkey-tests";
	name = name.substr(name.rfind('/') + 1);
	testing::UnitTest::GetInstance()->listeners().Append(new SummaryPrinter(name));
	return RUN_ALL_TESTS();
}
