// Issue 31: what the daemon's shared-memory output leaves behind. A rename
// (a reload with new [output] names) retires and removes the old objects, a
// clean stop (ShmFrameSink::remove) removes what it created, readers are
// told first (-ESTALE, then -ENOENT by name), and a name another writer
// holds is refused with -EBUSY and a sentence that says so.
#include "hal/depthkey_shm.h"
#include "hal/shm_frame_sink.hpp"
#include "hal/shm_ring_writer.hpp"
#include "tests/shm_test_util.hpp"

#include <gtest/gtest.h>

#include <memory>
#include <vector>

using namespace depthkey;
using depthkey::test::openStatus;
using depthkey::test::ShmName;

namespace {

// Three fresh names for one [output].
struct OutputNames {
	ShmName composite, lecturer, boardLecturer;
	OutputSettings settings() const
	{
		OutputSettings s;
		s.compositeName = composite.str();
		s.lecturerName = lecturer.str();
		s.boardLecturerName = boardLecturer.str();
		return s;
	}
};

} // namespace

TEST(ShmOutputLifecycle, RenamesRemoveTheOldObjectsOnceTheirReadersAreTold)
{
	std::vector<std::unique_ptr<OutputNames>> names;
	ShmFrameSink sink;
	for (int rename = 0; rename <= 10; rename++) {
		names.push_back(std::make_unique<OutputNames>());
		const OutputNames &now = *names.back();
		dk_shm_reader reader{};
		if (rename > 0) {
			ASSERT_EQ(dk_shm_open(names[names.size() - 2]->composite.c_str(), &reader), 0);
		}
		// Board geometry on even renames, camera geometry on odd ones: the
		// board layer's object goes too when it is renamed while closed.
		const int board = rename % 2 == 0 ? 32 : 0;
		ASSERT_EQ(sink.open(now.settings(), 16, 16, board, board), 0) << sink.describeError();
		if (rename > 0) {
			uint64_t frame = 0;
			EXPECT_EQ(dk_shm_latest(&reader, &frame), -ESTALE) << "the reader was not told";
			dk_shm_close(&reader);
		}
		EXPECT_EQ(openStatus(now.composite.c_str()), 0);
		EXPECT_EQ(openStatus(now.lecturer.c_str()), 0);
	}
	// Only the last names are left, whatever the renames did.
	for (size_t i = 0; i + 1 < names.size(); i++) {
		EXPECT_EQ(openStatus(names[i]->composite.c_str()), -ENOENT) << i;
		EXPECT_EQ(openStatus(names[i]->lecturer.c_str()), -ENOENT) << i;
		EXPECT_EQ(openStatus(names[i]->boardLecturer.c_str()), -ENOENT) << i;
	}
	EXPECT_EQ(openStatus(names.back()->boardLecturer.c_str()), 0);
}

TEST(ShmOutputLifecycle, ACleanStopRemovesWhatItCreated)
{
	OutputNames names;
	ShmFrameSink sink;
	ASSERT_EQ(sink.open(names.settings(), 16, 16, 32, 32), 0) << sink.describeError();
	dk_shm_reader reader{};
	ASSERT_EQ(dk_shm_open(names.lecturer.c_str(), &reader), 0);
	sink.remove();
	uint64_t frame = 0;
	EXPECT_EQ(dk_shm_latest(&reader, &frame), -ESTALE);
	dk_shm_close(&reader);
	EXPECT_EQ(openStatus(names.composite.c_str()), -ENOENT);
	EXPECT_EQ(openStatus(names.lecturer.c_str()), -ENOENT);
	EXPECT_EQ(openStatus(names.boardLecturer.c_str()), -ENOENT);
	sink.remove(); // twice is harmless
}

TEST(ShmOutputLifecycle, RemoveLeavesANameAnotherWriterTookOver)
{
	ShmName name;
	ShmRingWriter first, second;
	ASSERT_EQ(first.open(name.str(), 8, 8, DK_SHM_FORMAT_RGB24, 2, ""), 0);
	first.close();
	ASSERT_EQ(second.open(name.str(), 8, 8, DK_SHM_FORMAT_RGB24, 2, ""), 0);
	first.remove();
	EXPECT_EQ(openStatus(name.c_str()), 0) << "removed the other writer's object";
	EXPECT_EQ(second.unlink(), 0);
}

TEST(ShmOutputLifecycle, ANameAnotherWriterHoldsIsBusyAndSaysSo)
{
	OutputNames names;
	ShmFrameSink running, second;
	ASSERT_EQ(running.open(names.settings(), 16, 16), 0) << running.describeError();
	EXPECT_EQ(second.open(names.settings(), 16, 16), -EBUSY);
	EXPECT_NE(second.describeError().find(names.composite.str() + ": lock: another writer has it open"),
		  std::string::npos)
		<< second.describeError();
	// The second writer's failure took nothing from the first.
	EXPECT_EQ(openStatus(names.composite.c_str()), 0);
	second.remove();
	EXPECT_EQ(openStatus(names.composite.c_str()), 0);
	EXPECT_EQ(openStatus(names.lecturer.c_str()), 0);
}

// A second daemon that created its composite before finding the lecturer
// name busy removes that composite as it exits (FrameOutputs::open).
TEST(ShmOutputLifecycle, AnOpenThatFindsANameBusyRemovesWhatItCreated)
{
	OutputNames names;
	ShmRingWriter squatter;
	ASSERT_EQ(squatter.open(names.lecturer.str(), 8, 8, DK_SHM_FORMAT_RGBA32, 2, ""), 0);
	ShmFrameSink sink;
	ASSERT_EQ(sink.open(names.settings(), 16, 16), -EBUSY);
	EXPECT_EQ(openStatus(names.composite.c_str()), 0); // created, then closed
	sink.remove();
	EXPECT_EQ(openStatus(names.composite.c_str()), -ENOENT);
	EXPECT_EQ(openStatus(names.lecturer.c_str()), 0) << "the squatter's object is not ours to remove";
	EXPECT_EQ(squatter.unlink(), 0);
}
