#include "hal/sim/lecture_simulator.hpp"
#include "hal/sim/tof_artefacts.hpp"
#include "tests/sim_test_util.hpp"

#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>

using namespace depthkey;
using depthkey::test::cleanSim;

namespace {

struct Rendered {
	ColourFrame colour;
	GroundTruth truth;
	DepthFrame depth;
};

Rendered render(const SimSettings &s, double t)
{
	LectureSimulator sim;
	sim.configure(s, 640, 480);
	Rendered r;
	sim.renderColour(t, r.colour, &r.truth);
	sim.renderDepth(t, r.depth);
	return r;
}

// Where a point of the colour frame shows in the ToF image.
void tofPixelOf(const LectureSimulator &sim, Eigen::Vector3d p, int &u, int &v)
{
	double x, y;
	sim.rig().tof().project(sim.rig().toTof(p), x, y);
	u = static_cast<int>(std::lround(x));
	v = static_cast<int>(std::lround(y));
}

// Depth noise measured over many frames of an empty room around pixel
// (u, v) (3x3), as a ratio to the sigma the camera's own I and A predict,
// and the predicted sigma there in mm.
void noiseAt(LectureSimulator &sim, int u, int v, double &ratio, double &predictedMm)
{
	constexpr int kFrames = 60;
	double sum[9] = {}, sum2[9] = {}, sigma[9] = {};
	DepthFrame f;
	for (int i = 0; i < kFrames; ++i) {
		sim.renderDepth(0.1 * i, f);
		for (int k = 0; k < 9; ++k) {
			int x = u + k % 3 - 1, y = v + k / 3 - 1;
			double d = f.depthMm.at(x, y);
			sum[k] += d;
			sum2[k] += d * d;
			sigma[k] += 1000.0 * sim::tofSigmaM(f.intensity.at(x, y), f.amplitude.at(x, y)) / kFrames;
		}
	}
	double zsum = 0;
	predictedMm = 0;
	for (int k = 0; k < 9; ++k) {
		double var = (sum2[k] - sum[k] * sum[k] / kFrames) / (kFrames - 1);
		zsum += var / (sigma[k] * sigma[k]);
		predictedMm += sigma[k] / 9;
	}
	ratio = std::sqrt(zsum / 9);
}

int countDiffering(const Gray16Image &a, const Gray16Image &b, int tolerance)
{
	int n = 0;
	for (size_t i = 0; i < a.size(); ++i)
		n += std::abs(int(a.data()[i]) - int(b.data()[i])) > tolerance;
	return n;
}

} // namespace

TEST(LectureSimulator, SameSeedSameFramesOtherSeedOthers)
{
	SimSettings s;
	Rendered a = render(s, 3.7), b = render(s, 3.7);
	EXPECT_TRUE(a.colour.rgb == b.colour.rgb);
	EXPECT_TRUE(a.truth.alpha == b.truth.alpha);
	EXPECT_TRUE(a.depth.depthMm == b.depth.depthMm);
	EXPECT_TRUE(a.depth.amplitude == b.depth.amplitude);
	s.seed = 2;
	Rendered c = render(s, 3.7);
	EXPECT_FALSE(a.colour.rgb == c.colour.rgb);
	EXPECT_FALSE(a.depth.depthMm == c.depth.depthMm);
}

TEST(LectureSimulator, RenderingOrderDoesNotMatter)
{
	LectureSimulator sim;
	sim.configure(SimSettings{}, 640, 480);
	ColourFrame first, again, other;
	sim.renderColour(40.0, first); // another cycle: another slide
	sim.renderColour(2.0, other);
	sim.renderColour(40.0, again);
	EXPECT_TRUE(first.rgb == again.rgb);
}

TEST(LectureSimulator, GroundTruthHasTheLecturerWithSoftEdges)
{
	Rendered r = render(cleanSim(), 0.8);
	long inside = 0, edge = 0;
	for (size_t i = 0; i < r.truth.alpha.size(); ++i) {
		uint8_t a = r.truth.alpha.data()[i];
		inside += a == 255;
		edge += a > 0 && a < 255;
		ASSERT_EQ(r.truth.mask.data()[i], a >= 128 ? 255 : 0);
	}
	EXPECT_GT(inside, 20000); // a person at 1.3 m covers a good part of the picture
	EXPECT_GT(edge, 500);
	// The lecturer stands in front of the board: truth depth says so.
	for (size_t i = 0; i < r.truth.mask.size(); ++i) {
		if (r.truth.mask.data()[i]) {
			ASSERT_LT(r.truth.depthMm.data()[i], 1900);
		}
	}
}

TEST(LectureSimulator, DepthNoiseFollowsTheSr2FormulaCentreToEdge)
{
	SimSettings s = cleanSim();
	s.depthNoise = true;
	LectureSimulator sim;
	sim.configure(s, 640, 480);
	sim.setLecturerVisible(false);
	double ratio, centreMm, cornerMm, monitorMm;
	noiseAt(sim, 80, 40, ratio, centreMm);
	std::printf("ToF noise: centre predicted %.1f mm, measured/predicted %.3f\n", centreMm, ratio);
	EXPECT_NEAR(ratio, 1.0, 0.12);
	EXPECT_GT(centreMm, 15);
	EXPECT_LT(centreMm, 50); // "a few cm in the centre"
	noiseAt(sim, 2, 2, ratio, cornerMm);
	std::printf("ToF noise: corner predicted %.1f mm, measured/predicted %.3f\n", cornerMm, ratio);
	EXPECT_NEAR(ratio, 1.0, 0.12);
	EXPECT_GT(cornerMm, 200);
	EXPECT_LT(cornerMm, 330); // "up to 30 cm at the edge"
	// The monitor's glossy screen returns little light: noisier than the
	// board at a similar distance from the image centre.
	int u, v;
	tofPixelOf(sim, { 0.55, 0.05, 1.22 }, u, v);
	noiseAt(sim, u, v, ratio, monitorMm);
	double boardMm;
	noiseAt(sim, 2 * 80 - u, v, ratio, boardMm); // mirrored across the centre: board
	std::printf("ToF noise: monitor %.1f mm, board opposite %.1f mm\n", monitorMm, boardMm);
	EXPECT_GT(monitorMm, 1.5 * boardMm);
}

TEST(LectureSimulator, DepthNoiseSwitchesOff)
{
	LectureSimulator sim;
	sim.configure(cleanSim(), 640, 480);
	sim.setLecturerVisible(false);
	DepthFrame a, b;
	sim.renderDepth(1.0, a);
	sim.renderDepth(2.0, b);
	EXPECT_TRUE(a.depthMm == b.depthMm);
	// Board centre at its true distance (the ToF sees it at 2 m, tilted a little).
	EXPECT_NEAR(a.depthMm.at(80, 40), 2000, 40);
}

TEST(LectureSimulator, HaloMakesTheBoardCloserWithinItsWidth)
{
	SimSettings s = cleanSim();
	s.table = false;
	const double t = 0.8;
	Rendered off = render(s, t);
	s.haloWidthPx = 4;
	s.haloStrength = 0.5;
	Rendered on = render(s, t);
	const Gray16Image &a = off.depth.depthMm, &b = on.depth.depthMm;
	int maxDistance = 0, closer = 0, changed = 0;
	for (int y = 0; y < a.height(); ++y)
		for (int x = 0; x < a.width(); ++x) {
			int delta = int(b.at(x, y)) - int(a.at(x, y));
			if (std::abs(delta) <= 10 || a.at(x, y) < 1900)
				continue; // unchanged, or not board
			changed++;
			closer += delta < 0;
			// Chebyshev distance to the nearest lecturer pixel (depth < 1.9 m).
			int best = 1000;
			for (int yy = 0; yy < a.height(); ++yy)
				for (int xx = 0; xx < a.width(); ++xx)
					if (a.at(xx, yy) < 1900)
						best = std::min(best, std::max(std::abs(xx - x), std::abs(yy - y)));
			maxDistance = std::max(maxDistance, best);
		}
	std::printf("halo: %d board pixels changed, farthest %d px from the lecturer\n", changed, maxDistance);
	EXPECT_GT(changed, 100);
	EXPECT_EQ(closer, changed);
	EXPECT_GE(maxDistance, 3);
	EXPECT_LE(maxDistance, 5);
	s.haloStrength = 0;
	EXPECT_TRUE(render(s, t).depth.depthMm == a);
}

TEST(LectureSimulator, SaturationBlindsNearPixelsAndSwitchesOff)
{
	auto saturated = [](const DepthFrame &f) {
		int n = 0;
		for (size_t i = 0; i < f.depthMm.size(); ++i)
			n += f.depthMm.data()[i] == 0 && f.amplitude.data()[i] == 65535;
		return n;
	};
	SimSettings s = cleanSim();
	EXPECT_EQ(saturated(render(s, 0.8).depth), 0);
	s.saturationMm = 1500; // the talking lecturer (1.3 m) and the desk are nearer
	EXPECT_GT(saturated(render(s, 0.8).depth), 500);
}

TEST(LectureSimulator, MotionBlurMixesOnlyWhereThingsMove)
{
	SimSettings s = cleanSim();
	s.table = false;
	const double t = 0.9; // talking, the right hand circling fast
	Rendered sharp = render(s, t);
	s.motionBlur = true;
	Rendered blurred = render(s, t);
	int changed = countDiffering(sharp.depth.depthMm, blurred.depth.depthMm, 20);
	EXPECT_GT(changed, 5);
	EXPECT_LT(changed, 800); // the moving hand and arm, not the whole picture
}

TEST(LectureSimulator, DistortionSwitchMakesPinholes)
{
	SimSettings s = cleanSim();
	LectureSimulator sim;
	sim.configure(s, 640, 480);
	EXPECT_NE(sim.rig().colour().k1, 0.0);
	EXPECT_NE(sim.rig().tof().k1, 0.0);
	Rendered distorted = render(s, 1.0);
	s.distortion = false;
	sim.configure(s, 640, 480);
	EXPECT_EQ(sim.rig().colour().k1, 0.0);
	EXPECT_EQ(sim.rig().tof().k2, 0.0);
	EXPECT_FALSE(render(s, 1.0).colour.rgb == distorted.colour.rgb);
}

TEST(LectureSimulator, ColourNoiseHasItsSigmaAndSwitchesOff)
{
	auto flatSigma = [](const RgbImage &img) { // board top right: no strokes, no lecturer
		double sum = 0, sum2 = 0;
		int n = 0;
		for (int y = 40; y < 90; ++y)
			for (int x = 560; x < 630; ++x) {
				double v = img.at(x, y).g;
				sum += v;
				sum2 += v * v;
				n++;
			}
		return std::sqrt(sum2 / n - (sum / n) * (sum / n));
	};
	SimSettings s = cleanSim();
	EXPECT_LT(flatSigma(render(s, 0.5).colour.rgb), 0.01);
	s.colourNoise = 3.0;
	double sigma = flatSigma(render(s, 0.5).colour.rgb);
	EXPECT_NEAR(sigma, 3.0, 0.3);
}

TEST(LectureSimulator, LightingChangesSlowlyAndSwitchesOff)
{
	auto boardLevel = [](const RgbImage &img) {
		double sum = 0;
		for (int y = 40; y < 90; ++y)
			for (int x = 560; x < 630; ++x)
				sum += img.at(x, y).r + img.at(x, y).g + img.at(x, y).b;
		return sum / (50 * 70 * 3);
	};
	SimSettings s = cleanSim();
	EXPECT_EQ(boardLevel(render(s, 0.5).colour.rgb), boardLevel(render(s, 6.25).colour.rgb));
	s.lightingChange = true;
	s.lightingAmplitude = 0.3;
	double a = boardLevel(render(s, 0.5).colour.rgb), b = boardLevel(render(s, 6.25).colour.rgb);
	EXPECT_GT(std::fabs(a - b), 2.0); // a quarter period apart
	// Slowly: one frame later the light has hardly moved.
	EXPECT_NEAR(boardLevel(render(s, 0.54).colour.rgb), a, 0.5);
}

TEST(LectureSimulator, BoardIsWrittenWipedAndChangesSlides)
{
	// Chalk pixels on the board (bright, not the lecturer).
	auto ink = [](const Rendered &r) {
		int n = 0;
		for (int y = 0; y < 300; ++y)
			for (int x = 0; x < 640; ++x) {
				Rgb8 c = r.colour.rgb.at(x, y);
				n += r.truth.alpha.at(x, y) == 0 && c.r > 200 && c.g > 180 && r.truth.depthMm.at(x, y) > 1900;
			}
		return n;
	};
	SimSettings s = cleanSim();
	LectureSimulator probe;
	probe.configure(s, 640, 480);
	const double cycle = probe.script().cycleLength();
	int start = ink(render(s, 0.5));
	int written = ink(render(s, cycle * 0.62));
	int end = ink(render(s, cycle - 0.05));
	std::printf("board ink pixels: start %d, mid-cycle %d, end %d (cycle %.1f s)\n", start, written, end, cycle);
	EXPECT_EQ(start, 0);
	EXPECT_GT(written, 300);
	// Another cycle, another slide: the board's background differs.
	EXPECT_FALSE(render(s, 0.5).colour.rgb == render(s, cycle + 0.5).colour.rgb);
	s.boardChanges = false;
	EXPECT_GT(ink(render(s, 0.5)), 300); // everything written from the start
}

TEST(LectureSimulator, TableSwitch)
{
	SimSettings s = cleanSim();
	EXPECT_LT(render(s, 0.5).truth.depthMm.at(600, 450), 1400); // desk front at 1.05 m
	s.table = false;
	EXPECT_GT(render(s, 0.5).truth.depthMm.at(600, 450), 1900);
}

TEST(LectureSimulator, CalibrationTargetSeenByBothCameras)
{
	LectureSimulator sim;
	sim.configure(cleanSim(), 640, 480);
	sim::CalibrationTarget target;
	target.centre = { 0.0, 0.0, 1.2 };
	ColourFrame colour;
	GroundTruth truth;
	DepthFrame depth;
	sim.renderCalibrationPattern(target, 0.0, colour, depth);
	sim.renderColour(0.0, colour, &truth);
	// The centre circle (index 3, 2) is black in colour and dim in the ToF
	// amplitude; between circles the target is white and bright.
	double x, y;
	sim.rig().colour().project({ 0, 0, 1.2 }, x, y);
	EXPECT_LT(colour.rgb.at(int(x), int(y)).g, 60);
	sim.rig().colour().project({ 0.045, 0.045, 1.2 }, x, y);
	EXPECT_GT(colour.rgb.at(int(x), int(y)).g, 200);
	int u, v;
	tofPixelOf(sim, { 0, 0, 1.2 }, u, v);
	int ub, vb;
	tofPixelOf(sim, { 0.045, 0.045, 1.2 }, ub, vb);
	EXPECT_LT(depth.amplitude.at(u, v) * 5, depth.amplitude.at(ub, vb));
	EXPECT_NEAR(depth.depthMm.at(u, v), 1200, 30);
	// No lecturer while calibrating; removing the target brings the lecture back.
	for (size_t i = 0; i < truth.mask.size(); ++i)
		ASSERT_EQ(truth.mask.data()[i], 0);
	sim.setCalibrationTarget(std::nullopt);
	sim.renderColour(0.5, colour, &truth);
	EXPECT_GT(std::count(truth.mask.data(), truth.mask.data() + truth.mask.size(), 255), 1000);
}
