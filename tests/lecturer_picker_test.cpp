// LecturerPicker: which in-range area is the lecturer.

#include "algo/lecturer_picker.hpp"

#include <gtest/gtest.h>

using namespace depthkey;

namespace {

void fill(Gray8Image &image, int x0, int y0, int x1, int y1)
{
	for (int y = y0; y < y1; ++y)
		for (int x = x0; x < x1; ++x)
			image.at(x, y) = 255;
}

struct Scene {
	Gray8Image inRange{ 40, 30, 0 }, moving{ 40, 30, 0 };
	void desk() { fill(inRange, 20, 15, 40, 30); }       // 300 pixels, never moving
	void lecturer(int x, bool moves)                     // 10 x 20 = 200 pixels
	{
		fill(inRange, x, 5, x + 10, 25);
		if (moves)
			fill(moving, x, 5, x + 10, 25);
	}
};

int pickAndRemember(LecturerPicker &picker, Scene &scene, ComponentScratch &scratch, Gray8Image &chosen)
{
	chosen = scene.inRange;
	int size = picker.pick(chosen, scene.moving, scratch);
	picker.remember(chosen);
	return size;
}

} // namespace

TEST(LecturerPicker, FirstTheBiggestThenWhatMovesThenWhoWasThere)
{
	LecturerPicker picker;
	ComponentScratch scratch;
	Gray8Image chosen;

	Scene empty; // start-up in an empty room: the desk is the guess
	empty.desk();
	EXPECT_EQ(pickAndRemember(picker, empty, scratch, chosen), 300);

	Scene walksIn; // he walks in: the still desk is dropped for him
	walksIn.desk();
	walksIn.lecturer(2, true);
	EXPECT_EQ(pickAndRemember(picker, walksIn, scratch, chosen), 200);
	EXPECT_EQ(chosen.at(5, 10), 255);
	EXPECT_EQ(chosen.at(30, 20), 0);

	Scene standsStill; // he stands still (the background has taken him in), and
	standsStill.desk(); // a few pixels of the desk flicker: he is still the lecturer
	standsStill.lecturer(3, false);
	fill(standsStill.moving, 30, 20, 35, 25);
	EXPECT_EQ(pickAndRemember(picker, standsStill, scratch, chosen), 200);
	EXPECT_EQ(chosen.at(5, 10), 255);

	Scene left; // he has left: no lecturer, not the desk
	left.desk();
	EXPECT_EQ(pickAndRemember(picker, left, scratch, chosen), 0);
	EXPECT_EQ(chosen.at(30, 20), 0);

	picker.reset(); // a new start: the biggest again
	EXPECT_EQ(pickAndRemember(picker, left, scratch, chosen), 300);
}

TEST(LecturerPicker, AFewMovingPixelsDoNotMakeALecturer)
{
	LecturerPicker picker;
	ComponentScratch scratch;
	Gray8Image chosen;
	Scene start;
	start.lecturer(2, false);
	EXPECT_EQ(pickAndRemember(picker, start, scratch, chosen), 200); // the biggest
	Scene walks;
	walks.lecturer(4, true);
	EXPECT_EQ(pickAndRemember(picker, walks, scratch, chosen), 200); // confirmed: he moves
	Scene gone; // he left; the desk has fewer moving pixels than kMinMovingPixels
	gone.desk();
	fill(gone.moving, 30, 20, 33, 23);
	EXPECT_EQ(pickAndRemember(picker, gone, scratch, chosen), 0);
}
