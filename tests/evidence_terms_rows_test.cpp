// The fused evidence's row kernels (algo/evidence_terms_rows.hpp): the C
// rows against their definitions (the board distance against a double
// reference of the gained model, within half a level a channel; the colour
// change exactly), and the SSE2 and NEON rows against the C rows bit for
// bit, for any bytes, gains over the whole stated range, visits about the
// learned threshold, and runs of every length about the vector steps,
// unaligned; the still hold's stamps and flags too, with ages about the
// hold and across the 16-bit wrap.
#include "algo/board_model.hpp"
#include "algo/evidence_terms_rows.hpp"
#include "tests/simd_paths.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

using namespace depthkey;

namespace {

struct Rows {
	std::vector<Rgb8> colour, previous;
	std::vector<Rgba8> model;
};

Rows randomRows(std::mt19937 &rng, int n)
{
	Rows r;
	r.colour.resize(size_t(n));
	r.previous.resize(size_t(n));
	r.model.resize(size_t(n));
	auto byte = [&] { return uint8_t(rng()); };
	for (int x = 0; x < n; ++x) {
		r.colour[size_t(x)] = { byte(), byte(), byte() };
		// Half the previous pixels near the colour (the change that counts
		// is small), half anything.
		const Rgb8 c = r.colour[size_t(x)];
		r.previous[size_t(x)] = rng() % 2 ? Rgb8{ uint8_t(c.r ^ (rng() & 7)), uint8_t(c.g ^ (rng() & 7)), c.b }
						  : Rgb8{ byte(), byte(), byte() };
		r.model[size_t(x)] = { byte(), byte(), byte(), uint8_t(rng() % 4) };
	}
	return r;
}

} // namespace

static_assert(kEvidenceLearnedVisits == BoardModel::kLearnedVisits);

TEST(EvidenceTermsRows, TheCRowsMeetTheirDefinitions)
{
	std::mt19937 rng(28);
	const int n = 4096;
	const Rows r = randomRows(rng, n);
	std::vector<int16_t> distance(n), change(n);
	for (const auto &gain : { std::array{ 256, 256, 256 }, std::array{ 128, 300, 512 }, std::array{ 0, 1023, 777 } }) {
		boardDistanceRow_C(r.colour.data(), r.model.data(), gain.data(), n, distance.data());
		for (int x = 0; x < n; ++x) {
			const Rgba8 m = r.model[size_t(x)];
			const Rgb8 c = r.colour[size_t(x)];
			if (m.a < BoardModel::kLearnedVisits) {
				ASSERT_EQ(distance[size_t(x)], -1);
				continue;
			}
			const double reference = std::abs(c.r - m.r * gain[0] / 256.0) + std::abs(c.g - m.g * gain[1] / 256.0) +
						 std::abs(c.b - m.b * gain[2] / 256.0);
			ASSERT_NEAR(distance[size_t(x)], reference, 1.5) << "x " << x; // half a level a channel
		}
	}
	colourChangeRow_C(r.colour.data(), r.previous.data(), n, change.data());
	for (int x = 0; x < n; ++x) {
		const Rgb8 c = r.colour[size_t(x)], p = r.previous[size_t(x)];
		ASSERT_EQ(change[size_t(x)], std::abs(c.r - p.r) + std::abs(c.g - p.g) + std::abs(c.b - p.b));
	}
}

TEST(EvidenceTermsRows, EveryPathGivesTheCRowsValues)
{
	std::mt19937 rng(29);
	size_t compared = 0;
	for (int n : { 0, 1, 4, 5, 6, 7, 8, 9, 15, 16, 17, 31, 33, 64, 101 })
		for (int offset : { 0, 1, 3 })
			for (int trial = 0; trial < 6; ++trial) {
				const Rows r = randomRows(rng, n + offset);
				const int gain[3] = { int(rng() % 1024), int(128 + rng() % 385), int(rng() % 1024) };
				std::vector<int16_t> want(size_t(n) + 1, 7), got(size_t(n) + 1);
				boardDistanceRow_C(r.colour.data() + offset, r.model.data() + offset, gain, n, want.data());
				for (KernelPath path : simd_test::kAllPaths) {
					std::fill(got.begin(), got.end(), int16_t(7)); // the one past n stays
					boardDistanceRow(path)(r.colour.data() + offset, r.model.data() + offset, gain, n, got.data());
					ASSERT_EQ(got, want) << simd_test::pathName(path) << " distance n " << n << " offset " << offset;
				}
				colourChangeRow_C(r.colour.data() + offset, r.previous.data() + offset, n, want.data());
				for (KernelPath path : simd_test::kAllPaths) {
					std::fill(got.begin(), got.end(), int16_t(7));
					colourChangeRow(path)(r.colour.data() + offset, r.previous.data() + offset, n, got.data());
					ASSERT_EQ(got, want) << simd_test::pathName(path) << " change n " << n << " offset " << offset;
				}
				compared += size_t(n);
			}
	EXPECT_GT(compared, 5000u);
}

// The still hold: stamps of every age (some just set, some about holdFrames
// old, some from before the frame counter wrapped), changes about still and
// evidence about the pivot; the stamps written and the flags, every path
// against the C row, and the C row against the definition.
TEST(EvidenceTermsRows, EveryPathGivesTheStillHoldRowsStampsAndFlags)
{
	std::mt19937 rng(30);
	size_t compared = 0, held = 0;
	for (int n : { 0, 1, 7, 8, 9, 15, 16, 17, 33, 64, 101 })
		for (int trial = 0; trial < 12; ++trial) {
			const StillHold h{ int(1 + rng() % 60), int(rng() % 255), int(1 + rng() % 20),
					   uint16_t(trial % 3 ? rng() : rng() % 8) };
			std::vector<int16_t> change(static_cast<size_t>(n));
			std::vector<uint8_t> evidence(static_cast<size_t>(n));
			std::vector<uint16_t> moved(static_cast<size_t>(n)), inFront(static_cast<size_t>(n));
			for (int x = 0; x < n; ++x) {
				change[size_t(x)] = int16_t(rng() % 2 ? h.still - 1 + int(rng() % 3) : int(rng() % 766));
				evidence[size_t(x)] = uint8_t(rng() % 2 ? h.pivot + int(rng() % 3) - 1 : int(rng() & 255));
				auto age = [&] { return uint16_t(rng() % 2 ? h.holdFrames - 1 + int(rng() % 3) : int(rng())); };
				moved[size_t(x)] = uint16_t(h.frame - age());
				inFront[size_t(x)] = uint16_t(h.frame - age());
			}
			std::vector<uint16_t> wantMoved = moved, wantInFront = inFront;
			std::vector<uint8_t> want(size_t(n) + 1, 7);
			stillHoldRow_C(change.data(), evidence.data(), n, h, wantMoved.data(), wantInFront.data(), want.data());
			for (int x = 0; x < n; ++x) {
				const size_t i = size_t(x);
				ASSERT_EQ(wantMoved[i], change[i] >= h.still ? h.frame : moved[i]);
				ASSERT_EQ(wantInFront[i], evidence[i] > h.pivot ? h.frame : inFront[i]);
				const int movedAge = (h.frame - wantMoved[i] + 65536) % 65536;
				const int frontAge = (h.frame - wantInFront[i] + 65536) % 65536;
				ASSERT_EQ(want[i], movedAge < h.holdFrames && frontAge >= h.holdFrames ? 1 : 0);
				held += want[i];
			}
			for (KernelPath path : simd_test::kAllPaths) {
				std::vector<uint16_t> gotMoved = moved, gotInFront = inFront;
				std::vector<uint8_t> got(size_t(n) + 1, 7); // the one past n stays
				stillHoldRow(path)(change.data(), evidence.data(), n, h, gotMoved.data(), gotInFront.data(),
						   got.data());
				ASSERT_EQ(got, want) << simd_test::pathName(path) << " n " << n;
				ASSERT_EQ(gotMoved, wantMoved) << simd_test::pathName(path) << " n " << n;
				ASSERT_EQ(gotInFront, wantInFront) << simd_test::pathName(path) << " n " << n;
			}
			compared += size_t(n);
		}
	EXPECT_GT(compared, 2000u);
	EXPECT_GT(held, 50u); // both flags occur
	EXPECT_LT(held, compared - 50);
}
