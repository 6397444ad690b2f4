// Least-squares fitting of the mapping models and the calibration's model
// selection, on point sets generated from a known mapping.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "algo/calibration_fit.hpp"

namespace depthkey {
namespace {

// A mapping that neither model holds exactly: a lens with radial distortion
// and a 6 cm baseline seen through a slightly larger colour lens.
void rigTruth(double u, double v, double z, double &x2, double &y2)
{
	double xn = (u - 79.5) / 160.0, yn = (v - 61.5) / 160.0;
	double r2 = xn * xn + yn * yn;
	double k = 1 + 0.12 * r2;
	x2 = 319.5 + 520.0 * (xn * k + 0.06 / z) + 3.0;
	y2 = 239.5 + 520.0 * (yn * k + 0.004 / z) - 2.0;
}

MappingModel knownParallax()
{
	MappingModel m;
	m.kind = MappingKind::Parallax;
	m.x = { 322, 330, 2, 1.5, -0.8, 0.6, 20, -3, 18, 1, 30, -1.2, 0.7, 0.4 };
	m.y = { 238, -1, 245, 0.5, 1.1, -0.4, 2, 15, -1, 16, 2.5, 0.3, -0.9, -0.2 };
	return m;
}

// A 7x5 grid of ToF points across the image per view, at each depth; the
// colour points come from truth, plus Gaussian noise of sigma pixels.
template<typename Truth>
std::vector<CalibrationView> makeViews(std::initializer_list<double> depths, int viewsPerDepth,
				       Truth truth, double sigma = 0.0, uint32_t seed = 7)
{
	std::mt19937 rng(seed);
	std::normal_distribution<double> noise(0.0, sigma > 0 ? sigma : 1.0);
	std::vector<CalibrationView> views;
	for (double depth : depths) {
		for (int k = 0; k < viewsPerDepth; k++) {
			CalibrationView view{ depth, {} };
			double shiftU = 6.0 * k, shiftV = 4.0 * k;
			for (int row = 0; row < 5; row++) {
				for (int col = 0; col < 7; col++) {
					PointPair p;
					p.u = 8 + col * 20 + shiftU * (col % 2 ? 0.3 : 0.1);
					p.v = 8 + row * 24 + shiftV * 0.2;
					p.zMetres = depth + 0.002 * (col - 3);
					truth(p.u, p.v, p.zMetres, p.x2, p.y2);
					if (sigma > 0) {
						p.x2 += noise(rng);
						p.y2 += noise(rng);
					}
					view.points.push_back(p);
				}
			}
			views.push_back(view);
		}
	}
	return views;
}

std::vector<PointPair> allPoints(const std::vector<CalibrationView> &views)
{
	std::vector<PointPair> points;
	for (const CalibrationView &v : views)
		points.insert(points.end(), v.points.begin(), v.points.end());
	return points;
}

TEST(MappingFit, RecoversAParallaxModelExactly)
{
	MappingModel truth = knownParallax();
	auto views = makeViews({ 0.7, 1.2, 1.8, 2.4 }, 3, [&](double u, double v, double z, double &x, double &y) {
		truth.map(u, v, z, x, y);
	});
	MappingModel fitted;
	fitted.kind = MappingKind::Parallax;
	std::string error;
	ASSERT_EQ(fitMapping(allPoints(views), fitted, error), 0) << error;
	for (int i = 0; i < kMappingCoefficients; i++) {
		EXPECT_NEAR(fitted.x[i], truth.x[i], 1e-6) << "x" << i;
		EXPECT_NEAR(fitted.y[i], truth.y[i], 1e-6) << "y" << i;
	}
	EXPECT_LT(measureResiduals(fitted, allPoints(views)).maxPx, 1e-8);
}

TEST(MappingFit, RecoversAPaperModelExactly)
{
	MappingModel truth;
	truth.kind = MappingKind::Paper;
	truth.x = { 321, 335, 1.5, 12, -2.5 };
	truth.y = { 241, 250, -0.7, 9, 1.5 };
	auto views = makeViews({ 0.8, 1.6 }, 2, [&](double u, double v, double z, double &x, double &y) {
		truth.map(u, v, z, x, y);
	});
	MappingModel fitted;
	fitted.kind = MappingKind::Paper;
	std::string error;
	ASSERT_EQ(fitMapping(allPoints(views), fitted, error), 0) << error;
	for (int i = 0; i < 5; i++) {
		EXPECT_NEAR(fitted.x[i], truth.x[i], 1e-8) << "x" << i;
		EXPECT_NEAR(fitted.y[i], truth.y[i], 1e-8) << "y" << i;
	}
	EXPECT_EQ(fitted.x[5], 0.0);
}

TEST(MappingFit, NoiseGivesResidualsOfItsSize)
{
	MappingModel truth = knownParallax();
	auto views = makeViews({ 0.7, 1.2, 1.8, 2.4 }, 6, [&](double u, double v, double z, double &x, double &y) {
		truth.map(u, v, z, x, y);
	}, 0.3);
	MappingModel fitted;
	fitted.kind = MappingKind::Parallax;
	std::string error;
	ASSERT_EQ(fitMapping(allPoints(views), fitted, error), 0) << error;
	// Distance of two N(0, 0.3) axes: RMS 0.3 * sqrt(2), minus the few
	// degrees of freedom the fit absorbs.
	ResidualStats stats = measureResiduals(fitted, allPoints(views));
	EXPECT_NEAR(stats.rmsPx, 0.3 * std::sqrt(2.0), 0.05);
	EXPECT_GT(stats.maxPx, stats.rmsPx);
}

TEST(MappingFit, TooFewPointsIsAnError)
{
	MappingModel m;
	m.kind = MappingKind::Parallax;
	std::vector<PointPair> points(20);
	std::string error;
	EXPECT_EQ(fitMapping(points, m, error), -EINVAL);
	EXPECT_EQ(error, "20 points cannot fit the 14 coefficients per axis of model parallax");
}

TEST(MappingFit, OneDepthCannotDetermineTheDepthTerms)
{
	MappingModel truth = knownParallax();
	auto views = makeViews({ 1.2 }, 3, [&](double u, double v, double, double &x, double &y) {
		truth.map(u, v, 1.2, x, y);
	});
	for (CalibrationView &view : views)
		for (PointPair &p : view.points)
			p.zMetres = 1.2;
	MappingModel fitted;
	fitted.kind = MappingKind::Parallax;
	std::string error;
	EXPECT_EQ(fitMapping(allPoints(views), fitted, error), -EINVAL);
	EXPECT_NE(error.find("determine only 10 of the 14"), std::string::npos) << error;
}

TEST(CalibrationFit, PicksParallaxForAStereoRigAndReportsEveryDepth)
{
	auto views = makeViews({ 0.6, 1.0, 1.5, 2.0, 2.5 }, 4, rigTruth, 0.2);
	CalibrationFitOptions options;
	CalibrationFit fit;
	std::string error;
	std::vector<std::string> notes;
	ASSERT_EQ(fitCalibration(views, options, fit, error, notes), 0) << error;
	EXPECT_TRUE(notes.empty());
	ASSERT_EQ(fit.summaries.size(), 2u);
	EXPECT_EQ(fit.mapping.kind, MappingKind::Parallax);
	EXPECT_EQ(fit.selectedBy, "heldout");
	EXPECT_EQ(fit.heldOutViews, "every 4th view");
	EXPECT_EQ(fit.depthsM, (std::vector<double>{ 0.6, 1.0, 1.5, 2.0, 2.5 }));

	const CalibrationSummary &paper = fit.summaries[0];
	const CalibrationSummary &parallax = fit.summaries[1];
	EXPECT_EQ(parallax.fit.points, 15 * 35);        // 3 of every 4 views
	EXPECT_EQ(parallax.heldOut.points, 5 * 35);
	EXPECT_LT(parallax.heldOut.rmsPx, 0.4);
	// The paper's depth term is linear in z, parallax is 1/z: it is off most
	// at the ends of the range.
	EXPECT_GT(paper.heldOut.rmsPx, 2 * parallax.heldOut.rmsPx);

	// A row per model, set and depth.
	EXPECT_EQ(fit.residuals.size(), 2u * 2u * 5u);
	for (const CalibrationResidual &r : fit.residuals)
		EXPECT_GT(r.stats.points, 0);
}

TEST(CalibrationFit, ModelOptionOverridesTheHeldOutChoice)
{
	auto views = makeViews({ 0.6, 1.0, 1.5, 2.0, 2.5 }, 4, rigTruth, 0.2);
	CalibrationFitOptions options;
	options.model = MappingKind::Paper;
	CalibrationFit fit;
	std::string error;
	std::vector<std::string> notes;
	ASSERT_EQ(fitCalibration(views, options, fit, error, notes), 0) << error;
	EXPECT_EQ(fit.mapping.kind, MappingKind::Paper);
	EXPECT_EQ(fit.selectedBy, "option");
	ASSERT_EQ(fit.summaries.size(), 1u);
}

TEST(CalibrationFit, HoldingOutADepthReportsItAsHeldOutOnly)
{
	auto views = makeViews({ 0.6, 1.0, 1.5, 2.0, 2.5 }, 2, rigTruth, 0.2);
	CalibrationFitOptions options;
	options.holdOutDepthM = 1.5;
	CalibrationFit fit;
	std::string error;
	std::vector<std::string> notes;
	ASSERT_EQ(fitCalibration(views, options, fit, error, notes), 0) << error;
	EXPECT_EQ(fit.heldOutViews, "views at 1.5 m");
	EXPECT_EQ(fit.depthsM, (std::vector<double>{ 0.6, 1.0, 2.0, 2.5 }));
	for (const CalibrationResidual &r : fit.residuals)
		EXPECT_EQ(r.heldOut, r.depthM == 1.5);
}

TEST(CalibrationFit, TwoDepthsFitOnlyThePaperModel)
{
	auto views = makeViews({ 1.0, 2.0 }, 4, rigTruth, 0.2);
	CalibrationFit fit;
	std::string error;
	std::vector<std::string> notes;
	ASSERT_EQ(fitCalibration(views, {}, fit, error, notes), 0) << error;
	EXPECT_EQ(fit.mapping.kind, MappingKind::Paper);
	EXPECT_EQ(notes, std::vector<std::string>{ "model parallax: needs views at 3 depths or more, has 2" });
}

TEST(CalibrationFit, NoHeldOutViewIsAnError)
{
	auto views = makeViews({ 1.0, 1.5, 2.0 }, 1, rigTruth);
	CalibrationFit fit;
	std::string error;
	std::vector<std::string> notes;
	EXPECT_EQ(fitCalibration(views, {}, fit, error, notes), -EINVAL);
	EXPECT_EQ(error, "no view is held out (every 4th view of 3 views), so the models cannot be "
			 "compared: take more views");
}

// The pipeline remaps when the model differs in anything: each field alone
// makes two models unequal.
TEST(MappingModel, EqualityCoversEveryField)
{
	const MappingModel base = knownParallax();
	EXPECT_EQ(base, knownParallax());
	std::vector<MappingModel> changed(7, base);
	changed[0].kind = MappingKind::Identity;
	changed[1].colourWidth += 1;
	changed[2].colourHeight += 1;
	changed[3].tofWidth += 1;
	changed[4].tofHeight += 1;
	changed[5].x[3] += 1e-9;
	changed[6].y[0] -= 1e-9;
	ASSERT_NE(base.kind, MappingKind::Identity);
	for (size_t i = 0; i < changed.size(); ++i)
		EXPECT_FALSE(changed[i] == base) << "field " << i;
}

} // namespace
} // namespace depthkey
