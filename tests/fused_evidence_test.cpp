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

// Depth evidence values (DepthSeeder::depthEvidence): clean depth on his
// surface, clean depth on the board, and a mixed pixel at his silhouette
// leaning his way.
constexpr int kDepthSaysLecturer = 254, kDepthSaysBoard = 1, kDepthAtTheEdge = 176;

double fuseReference(const DecisionSettings &s, int siox, int depthEvidence, int boardDistance, int previousAlpha,
		     int change)
{
	double sum = siox - 128.0;
	if (boardDistance >= 0 && boardDistance < s.boardMatch)
		sum -= s.boardWeight * double(s.boardMatch - boardDistance) / s.boardMatch;
	else if (boardDistance > 2 * s.boardMatch)
		sum += s.boardWeight * std::min(boardDistance - 2.0 * s.boardMatch, double(s.boardMatch)) /
		       (2.0 * s.boardMatch);
	if (previousAlpha >= 0 && change < s.stillColour)
		sum += s.temporalWeight * (previousAlpha - 128.0) / 128.0 * (s.stillColour - change) / s.stillColour;
	sum = std::clamp(sum, -127.0, 127.0); // the colour camera's say, capped
	sum += s.depthWeight * (depthEvidence - s.depthPivot) / 64.0;
	return std::clamp(sum + 128.0, 1.0, 255.0);
}

} // namespace

TEST(FusedEvidence, FixedPointMatchesTheDoubleReferenceWithinTwoUnits)
{
	const DecisionSettings s;
	std::map<int, int> histogram;
	int worst = 0;
	for (int siox = 1; siox <= 255; siox += 7)
		for (int depth = 0; depth <= 255; depth += 11)
			for (int board = -1; board < 120; board += 9)
				for (int previous = -1; previous <= 255; previous += 64)
					for (int change = 0; change < 40; change += 13) {
						const int fixed = FusedEvidence::fuse(s, siox, depth, board, previous, change);
						const double ref = fuseReference(s, siox, depth, board, previous, change);
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
	// Colour ambiguous: clean depth decides.
	EXPECT_GE(FusedEvidence::fuse(s, neutralColour, kDepthSaysLecturer, noModel, noPrevious, 0),
		  kConfidenceLecturer);
	EXPECT_LT(FusedEvidence::fuse(s, neutralColour, kDepthSaysBoard, noModel, noPrevious, 0), kConfidenceLecturer);
	// Clean depth outweighs a clear colour either way (a dark sleeve on
	// the dark board; a white shirt's colour on the board beside him).
	EXPECT_GE(FusedEvidence::fuse(s, 20, kDepthSaysLecturer, noModel, noPrevious, 0), kConfidenceLecturer);
	EXPECT_LT(FusedEvidence::fuse(s, 236, kDepthSaysBoard, noModel, noPrevious, 0), kConfidenceLecturer);
	// Colour says lecturer (white chalk like a white shirt), depth at its
	// edge: the board model's match at this pixel says board.
	EXPECT_GE(FusedEvidence::fuse(s, 200, kDepthAtTheEdge, noModel, noPrevious, 0), kConfidenceLecturer);
	EXPECT_LT(FusedEvidence::fuse(s, 200, kDepthAtTheEdge, 2, noPrevious, 0), kConfidenceLecturer);
	// Colour says board (a dark vest on the dark board) but the pixel is
	// far from how the board looks there, and in range: lecturer.
	EXPECT_GE(FusedEvidence::fuse(s, 60, kDepthAtTheEdge, 90, noPrevious, 0), kConfidenceLecturer);
	// The previous frame counts only where the colour did not change.
	const int still = FusedEvidence::fuse(s, neutralColour, s.depthPivot, noModel, 255, 0);
	const int moved = FusedEvidence::fuse(s, neutralColour, s.depthPivot, noModel, 255, s.stillColour);
	EXPECT_GT(still, moved);
	EXPECT_EQ(moved, FusedEvidence::fuse(s, neutralColour, s.depthPivot, noModel, noPrevious, 0));
}
