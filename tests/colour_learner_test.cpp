// ColourLearner: provisional signatures from the first frame, board colours
// only well away from the lecturer, and colours that came from the seeds'
// errors left out of a signature.

#include "algo/colour_learner.hpp"
#include "algo/trimap.hpp"

#include <gtest/gtest.h>

using namespace depthkey;

namespace {

constexpr Rgb8 kShirt{ 200, 40, 40 }, kBoard{ 30, 60, 40 }, kStripe{ 40, 200, 40 };

// 200 x 100: the lecturer (trimap lecturer) in columns [0, 80) wearing
// kShirt, the board elsewhere; columns [80, 90) are a kStripe stripe on the
// board right beside him. contamination: every n-th lecturer pixel shows the
// board (the board seen through a gap the depth camera cannot resolve).
void scene(RgbImage &colour, Gray8Image &trimap, int contamination)
{
	colour = RgbImage(200, 100, kBoard);
	trimap = Gray8Image(200, 100, kTrimapBoard);
	for (int y = 0; y < 100; ++y)
		for (int x = 0; x < 90; ++x) {
			if (x < 80) {
				trimap.at(x, y) = kTrimapLecturer;
				bool gap = contamination && (x + y * 80) % contamination == 0;
				colour.at(x, y) = gap ? kBoard : kShirt;
			} else {
				colour.at(x, y) = kStripe;
			}
		}
}

bool nearAny(const ColourSignature &signature, Lab16 lab, uint32_t within)
{
	return signature.nearest(lab) <= within;
}

} // namespace

TEST(ColourLearner, ProvisionalSignaturesFromTheFirstFrame)
{
	QuantisedLab lab;
	SioxClassifier classifier(lab);
	ColourLearner learner(lab);
	LearningSettings settings;
	settings.initialFrames = 5;
	learner.configure(settings);
	RgbImage colour;
	Gray8Image trimap;
	scene(colour, trimap, 0);
	EXPECT_TRUE(learner.learn(colour, trimap, 4, classifier));
	EXPECT_TRUE(learner.learning());
	EXPECT_GE(classifier.confidence(quantiseColour(kShirt)), kConfidenceLecturer);
	EXPECT_LT(classifier.confidence(quantiseColour(kBoard)), kConfidenceLecturer);
	for (int i = 1; i < 5; ++i)
		EXPECT_TRUE(learner.learn(colour, trimap, 4, classifier)) << i; // every frame while learning
	EXPECT_FALSE(learner.learning());
	EXPECT_EQ(learner.derivations(), 5);
	EXPECT_FALSE(learner.learn(colour, trimap, 4, classifier)); // nothing changed: no re-derivation
}

TEST(ColourLearner, BoardColoursAreLearnedOnlyBeyondTheMargin)
{
	QuantisedLab lab;
	const Lab16 stripe = lab[quantiseColour(kStripe)], board = lab[quantiseColour(kBoard)];
	for (int margin : { 4, 12 }) {
		SioxClassifier classifier(lab);
		ColourLearner learner(lab);
		learner.configure(LearningSettings{});
		RgbImage colour;
		Gray8Image trimap;
		scene(colour, trimap, 0);
		learner.learn(colour, trimap, margin, classifier);
		EXPECT_TRUE(nearAny(classifier.board(), board, 100));
		// The stripe is 10 pixels wide: learned with a 4 pixel margin, not with 12.
		EXPECT_EQ(nearAny(classifier.board(), stripe, 100), margin == 4) << margin;
	}
}

TEST(ColourLearner, BoardSeenThroughTheSeedsIsLeftOutOfTheLecturer)
{
	QuantisedLab lab;
	const Lab16 board = lab[quantiseColour(kBoard)];
	SioxClassifier classifier(lab);
	ColourLearner learner(lab);
	learner.configure(LearningSettings{});
	RgbImage colour;
	Gray8Image trimap;
	scene(colour, trimap, 10); // 10 % of the lecturer's samples are board
	learner.learn(colour, trimap, 4, classifier);
	EXPECT_FALSE(nearAny(classifier.lecturer(), board, 10000));
	EXPECT_LT(classifier.confidence(quantiseColour(kBoard)), 20);
	EXPECT_GE(classifier.confidence(quantiseColour(kShirt)), 240);
}
