// The simulated colour camera makes its frames where the daemon lends it
// storage (Camera::lendFrames: the pairing ring's free slot), and in its own
// buffer when none is lent, numbering them in one sequence either way.
#include "hal/event_loop.hpp"
#include "hal/sim/sim_cameras.hpp"

#include <gtest/gtest.h>

#include <vector>

using namespace depthkey;

TEST(SimColourCamera, MakesItsFramesInLentStorageWhenLent)
{
	EventLoop loop;
	ASSERT_EQ(loop.open(), 0);
	ColourCameraSettings colour;
	colour.width = 64;
	colour.height = 48;
	colour.fps = 50;
	SimColourCamera camera(colour, SimSettings{});
	ColourFrame lent;
	int asked = 0;
	// Lends every other frame: the others are made in the camera's own.
	camera.lendFrames([&]() -> ColourFrame * { return asked++ % 2 == 0 ? &lent : nullptr; });
	std::vector<const ColourFrame *> where;
	std::vector<uint64_t> sequences;
	ASSERT_EQ(camera.start(
			  loop,
			  [&](const ColourFrame &f) {
				  where.push_back(&f);
				  sequences.push_back(f.sequence);
				  EXPECT_EQ(f.rgb.width(), 64);
				  EXPECT_EQ(f.rgb.height(), 48);
				  if (where.size() == 4)
					  loop.exit(0);
			  },
			  [](const DeviceStatus &) {}),
		  0);
	EventSource timeout;
	ASSERT_EQ(loop.addTimer(5'000'000, [&] { loop.exit(1); }, timeout), 0);
	ASSERT_EQ(loop.run(), 0);
	camera.stop();
	ASSERT_EQ(where.size(), 4u);
	EXPECT_EQ(where[0], &lent);
	EXPECT_NE(where[1], &lent);
	EXPECT_EQ(where[2], &lent);
	EXPECT_EQ(where[3], where[1]);
	EXPECT_EQ(sequences, (std::vector<uint64_t>{ 1, 2, 3, 4 }));
	EXPECT_EQ(asked, 4);
}
