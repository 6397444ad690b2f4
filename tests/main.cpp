// GoogleTest main for depthkey-tests. Besides gtest's own report it prints one
// closing line "depthkey-tests: N passed, N failed, N skipped" so that CI can
// count the tests whatever runner it knows.
#include <gtest/gtest.h>

#include <cstdio>

namespace {

class SummaryPrinter : public testing::EmptyTestEventListener
{
	void OnTestProgramEnd(const testing::UnitTest &unit) override
	{
		std::printf("depthkey-tests: %d passed, %d failed, %d skipped\n",
			    unit.successful_test_count(), unit.failed_test_count(),
			    unit.skipped_test_count());
		std::fflush(stdout);
	}
};

} // namespace

int main(int argc, char **argv)
{
	testing::InitGoogleTest(&argc, argv);
	testing::UnitTest::GetInstance()->listeners().Append(new SummaryPrinter);
	return RUN_ALL_TESTS();
}
