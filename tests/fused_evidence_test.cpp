// The evidence fusion kernel against a double reference (tolerance: 2
// confidence units, one per truncating division), and the direction of each
// term: depth, the board model and the previous frame move the decision the
// way they should.
#include <gtest/gtest.h>

#include "algo/fused_evidence.hpp"

#include <algorithm>
#include <cmath>
#include <map>

using namespace depthkey;

namespace {

double fuseReference(const DecisionSettings &s, int siox, int trimap, int boardDistance, int previousAlpha,
		     int change)
{
	double sum = siox - 128.0;
	sum += s.depthWeight * (trimap - s.depthPivot) / 64.0;
	if (boardDistance >= 0 && boardDistance < s.boardMatch)
		sum -= s.boardWeight * double(s.boardMatch - boardDistance) / s.boardMatch;
	else if (boardDistance > 2 * s.boardMatch)
		sum += s.boardWeight * std::min(boardDistance - 2.0 * s.boardMatch, double(s.boardMatch)) /
		       (2.0 * s.boardMatch);
	if (previousAlpha >= 0 && change < s.stillColour)
		sum += s.temporalWeight * (previousAlpha - 128.0) / 128.0 * (s.stillColour - change) / s.stillColour;
	return std::clamp(sum + 128.0, 1.0, 255.0);
}

} // namespace

TEST(FusedEvidence, FixedPointMatchesTheDoubleReferenceWithinTwoUnits)
{
	const DecisionSettings s;
	std::map<int, int> histogram;
	int worst = 0;
	for (int siox = 1; siox <= 255; siox += 7)
		for (int trimap = 1; trimap <= 254; trimap += 11)
			for (int board = -1; board < 120; board += 9)
				for (int previous = -1; previous <= 255; previous += 64)
					for (int change = 0; change < 40; change += 13) {
						const int fixed = FusedEvidence::fuse(s, siox, trimap, board, previous, change);
						const double ref = fuseReference(s, siox, trimap, board, previous, change);
						const int error = int(std::ceil(std::abs(fixed - ref) - 1e-9));
						histogram[error]++;
						worst = std::max(worst, error);
					}
	std::printf("fused confidence, fixed vs double, |error| histogram:");
	for (auto [e, n] : histogram)
		std::printf(" %d:%d", e, n);
	std::printf("\n");
	EXPECT_LE(worst, 2);
}

TEST(FusedEvidence, EachTermPullsItsWay)
{
	const DecisionSettings s;
	const int neutralColour = 128, noModel = -1, noPrevious = -1;
	// Colour ambiguous: depth decides (deep in range -> lecturer, out of
	// range -> board).
	EXPECT_GE(FusedEvidence::fuse(s, neutralColour, kTrimapSubset, noModel, noPrevious, 0), kConfidenceLecturer);
	EXPECT_LT(FusedEvidence::fuse(s, neutralColour, kTrimapUndecided, noModel, noPrevious, 0), kConfidenceLecturer);
	// Colour says lecturer (white chalk like a white shirt), depth at its
	// edge: the board model's match at this pixel says board.
	EXPECT_GE(FusedEvidence::fuse(s, 200, kTrimapInRange, noModel, noPrevious, 0), kConfidenceLecturer);
	EXPECT_LT(FusedEvidence::fuse(s, 200, kTrimapInRange, 2, noPrevious, 0), kConfidenceLecturer);
	// Colour says board (a dark vest on the dark board) but the pixel is
	// far from how the board looks there, and in range: lecturer.
	EXPECT_GE(FusedEvidence::fuse(s, 60, kTrimapInRange, 90, noPrevious, 0), kConfidenceLecturer);
	// The previous frame counts only where the colour did not change.
	const int still = FusedEvidence::fuse(s, neutralColour, s.depthPivot, noModel, 255, 0);
	const int moved = FusedEvidence::fuse(s, neutralColour, s.depthPivot, noModel, 255, s.stillColour);
	EXPECT_GT(still, moved);
	EXPECT_EQ(moved, FusedEvidence::fuse(s, neutralColour, s.depthPivot, noModel, noPrevious, 0));
}
