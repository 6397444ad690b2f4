// The NO SIGNAL frame and the stage pictures, drawn by the project itself
// since the daemon links no drawing library (issue 15).
#include <gtest/gtest.h>

#include "algo/no_signal_frame.hpp"
#include "algo/trimap.hpp"
#include "hal/preview/stage_picture.hpp"

using namespace depthkey;

namespace {

// White pixels (the text): how many, and whether any touches the left or right edge.
int whitePixels(const RgbImage &image, bool &touchesSide)
{
	int n = 0;
	touchesSide = false;
	for (int y = 0; y < image.height(); ++y)
		for (int x = 0; x < image.width(); ++x)
			if (image.at(x, y) == (Rgb8{ 255, 255, 255 })) {
				++n;
				touchesSide |= x < 4 || x >= image.width() - 4;
			}
	return n;
}

} // namespace

TEST(NoSignalFrame, BarsAndTheTextInsideThePictureAtAnySize)
{
	for (auto [w, h] : { std::pair{ 640, 480 }, std::pair{ 160, 120 }, std::pair{ 1920, 1080 } }) {
		RgbImage frame(w, h);
		renderNoSignalFrame("NO SIGNAL: v4l2 /dev/video0", frame);
		EXPECT_EQ(frame.at(0, 0), (Rgb8{ 96, 96, 96 })) << w; // the first bar, grey
		EXPECT_EQ(frame.at(w - 1, h - 1), (Rgb8{ 0, 0, 96 })) << w; // the last, blue
		EXPECT_EQ(frame.at(w / 2, 2), (Rgb8{ 0, 96, 0 })) << w;     // the middle one, green
		bool touchesSide = false;
		EXPECT_GT(whitePixels(frame, touchesSide), 100) << w;
		EXPECT_FALSE(touchesSide) << w << ": the text is wrapped onto lines that fit";
	}
}

TEST(StagePicture, DepthInFalseColourSeedsInThreeColoursSmallImagesEnlarged)
{
	Gray16Image depth(160, 124, 0);
	depth.at(1, 1) = 500;  // near: the warm end
	depth.at(2, 1) = 4000; // far: the cold end
	StageImage depthStage{ "depth", StageKind::Depth, nullptr, &depth, nullptr };
	StagePicture picture = drawStagePicture(depthStage);
	ASSERT_EQ(picture.width(), 640) << "the ToF's 160 columns, 4x";
	EXPECT_EQ(picture.rgb.at(0, 0), (Rgb8{ 0, 0, 0 })) << "no measurement";
	EXPECT_EQ(picture.rgb.at(4 + 3, 4), (Rgb8{ 128, 0, 0 })) << "0.5 m: dark red";
	EXPECT_EQ(picture.rgb.at(8, 7), (Rgb8{ 0, 0, 128 })) << "4 m: dark blue";

	Gray8Image seeds(320, 2, kTrimapUndecided);
	seeds.at(0, 0) = kTrimapBoard;
	seeds.at(1, 0) = kTrimapLecturer;
	StageImage seedStage{ "seeds", StageKind::Seeds, nullptr, nullptr, &seeds };
	picture = drawStagePicture(seedStage);
	ASSERT_EQ(picture.width(), 320);
	EXPECT_EQ(picture.rgb.at(0, 0), (Rgb8{ 40, 80, 200 }));
	EXPECT_EQ(picture.rgb.at(1, 0), (Rgb8{ 255, 140, 0 }));
	EXPECT_EQ(picture.rgb.at(2, 0), (Rgb8{ 128, 128, 128 }));

	StageImage maskStage{ "alpha", StageKind::Mask, nullptr, nullptr, &seeds };
	picture = drawStagePicture(maskStage);
	EXPECT_TRUE(picture.rgb.empty());
	EXPECT_EQ(picture.gray, seeds);
	EXPECT_TRUE(drawStagePicture(StageImage{ "none", StageKind::Colour }).empty());
}
