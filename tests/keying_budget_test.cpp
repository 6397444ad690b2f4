// The daemon's keying budget (daemon/keying_budget.hpp) on a fake clock: a
// box that keeps up never sheds, a slow one keys with three quarters of the
// loop's time and sheds the rest.
#include "daemon/keying_budget.hpp"

#include <gtest/gtest.h>

using namespace depthkey;

namespace {

struct Outcome {
	uint64_t keyed = 0, shed = 0, keyingUs = 0, elapsedUs = 0;
};

// Colour frames every periodUs for seconds; each keyed one holds the loop
// for keyingUs, and a frame due meanwhile is handed over when it ends (as a
// camera's queue does).
Outcome simulate(KeyingBudget &budget, uint64_t periodUs, uint64_t keyingUs, double seconds, uint64_t startUs = 0)
{
	Outcome run;
	uint64_t loopFreeUs = startUs;
	const uint64_t frames = uint64_t(seconds * 1e6 / double(periodUs));
	for (uint64_t i = 0; i < frames; ++i) {
		const uint64_t nowUs = std::max(startUs + i * periodUs, loopFreeUs);
		if (budget.admit(nowUs)) {
			budget.spend(keyingUs);
			run.keyed++;
			run.keyingUs += keyingUs;
			loopFreeUs = nowUs + keyingUs;
		} else {
			run.shed++;
			loopFreeUs = nowUs;
		}
		run.elapsedUs = loopFreeUs - startUs;
	}
	return run;
}

} // namespace

TEST(KeyingBudget, ABoxThatKeepsUpNeverSheds)
{
	KeyingBudget budget;
	// 21 ms a frame at 30 fps (the native figure at 640x480), for ten minutes.
	Outcome run = simulate(budget, 33333, 21000, 600);
	EXPECT_EQ(run.shed, 0u);
	EXPECT_EQ(budget.shed(), 0u);
}

TEST(KeyingBudget, ASlowBoxKeysWithThreeQuartersOfTheLoop)
{
	KeyingBudget budget;
	// The HIL VM: 180 ms a frame at 15 fps, for a minute.
	Outcome run = simulate(budget, 66667, 180000, 60);
	const double share = double(run.keyingUs) / double(run.elapsedUs);
	std::printf("keyed %llu, shed %llu, keying %.3f of the loop\n", static_cast<unsigned long long>(run.keyed),
		    static_cast<unsigned long long>(run.shed), share);
	EXPECT_GT(run.shed, 0u);
	EXPECT_EQ(budget.shed(), run.shed);
	// The saved burst and one frame's overdraft above the share.
	EXPECT_LE(double(run.keyingUs), 0.75 * double(run.elapsedUs) + KeyingBudget::kBurstUs + 180000);
	EXPECT_GE(double(run.keyingUs), 0.75 * double(run.elapsedUs) - 180000 - 66667) << "sheds more than it must";
}

TEST(KeyingBudget, AnIdleLoopSavesOnlyABurst)
{
	KeyingBudget budget;
	EXPECT_TRUE(budget.admit(0));
	// An hour without frames (no camera) saves a burst, not an hour.
	Outcome run = simulate(budget, 10000, 100000, 3, 3600ull * 1000000);
	EXPECT_LE(double(run.keyingUs), 0.75 * double(run.elapsedUs) + KeyingBudget::kBurstUs + 100000);
	EXPECT_GT(run.shed, 0u);
}

TEST(KeyingBudget, ABurstAfterAHeldLoopIsKeyedInFull)
{
	KeyingBudget budget;
	simulate(budget, 66667, 10000, 10); // keeping up
	// The loop was held for 700 ms: ten frames wait and come at once.
	const uint64_t nowUs = 10'700'000;
	for (int i = 0; i < 10; ++i) {
		EXPECT_TRUE(budget.admit(nowUs)) << "frame " << i;
		budget.spend(10000);
	}
}

TEST(KeyingBudget, ALowerShareLeavesTheLoopMoreTime)
{
	// daemon.keying_share = 40: the HIL VM's 180 ms frames at 10 fps key
	// with two fifths of the loop, where the default keys with three quarters.
	KeyingBudget lower, standard;
	lower.setSharePercent(40);
	Outcome low = simulate(lower, 100000, 180000, 60);
	Outcome high = simulate(standard, 100000, 180000, 60);
	const double lowShare = double(low.keyingUs) / double(low.elapsedUs);
	const double highShare = double(high.keyingUs) / double(high.elapsedUs);
	std::printf("share 40: keying %.3f of the loop, %llu shed; share 75: %.3f, %llu shed\n", lowShare,
		    static_cast<unsigned long long>(low.shed), highShare, static_cast<unsigned long long>(high.shed));
	EXPECT_NEAR(lowShare, 0.40, 0.03);
	EXPECT_NEAR(highShare, 0.75, 0.03);
	// Out-of-range settings are held to 10..100 percent.
	KeyingBudget tiny, all;
	tiny.setSharePercent(0);
	all.setSharePercent(1000);
	EXPECT_NEAR(double(simulate(tiny, 100000, 180000, 60).keyingUs) / 60e6, 0.10, 0.02);
	EXPECT_EQ(simulate(all, 100000, 180000, 60).shed, 0u);
}
