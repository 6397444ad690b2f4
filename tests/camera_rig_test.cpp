#include "algo/mapping_model.hpp"
#include "hal/sim/camera_rig.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>
#include <vector>

using namespace depthkey;

namespace {

struct Correspondence {
	double u, v, z, x, y;
};

// Every 4th ToF pixel at depths 0.5..2.5 m whose true image lies in the
// colour picture: the domain issue 7's calibration must cover.
std::vector<Correspondence> sampleRig(const CameraRig &rig)
{
	std::vector<Correspondence> points;
	for (double z = 0.5; z <= 2.501; z += 0.25)
		for (int v = 0; v < rig.tof().height; v += 3)
			for (int u = 0; u < rig.tof().width; u += 3) {
				double x, y;
				if (!rig.tofToColour(u, v, z, x, y))
					continue;
				if (x < -0.5 || y < -0.5 || x > rig.colour().width - 0.5 ||
				    y > rig.colour().height - 0.5)
					continue;
				points.push_back({ double(u), double(v), z, x, y });
			}
	return points;
}

// Least-squares fit of one model kind; returns the RMS residual in pixels.
double fitRms(const CameraRig &rig, MappingKind kind, const std::vector<Correspondence> &points)
{
	MappingModel model;
	model.kind = kind;
	model.colourWidth = rig.colour().width;
	model.colourHeight = rig.colour().height;
	model.tofWidth = rig.tof().width;
	model.tofHeight = rig.tof().height;
	for (int axis = 0; axis < 2; ++axis) {
		std::array<double, kMappingCoefficients> b;
		int n = model.basis(0, 0, 1, axis == 1, b);
		Eigen::MatrixXd a(points.size(), n);
		Eigen::VectorXd rhs(points.size());
		for (size_t i = 0; i < points.size(); ++i) {
			double s, t;
			model.normalise(points[i].u, points[i].v, s, t);
			model.basis(s, t, points[i].z, axis == 1, b);
			for (int j = 0; j < n; ++j)
				a(i, j) = b[j];
			rhs(i) = axis ? points[i].y : points[i].x;
		}
		Eigen::VectorXd c = a.colPivHouseholderQr().solve(rhs);
		auto &dst = axis ? model.y : model.x;
		for (int j = 0; j < n; ++j)
			dst[j] = c(j);
	}
	double sum = 0;
	for (const Correspondence &p : points) {
		double x, y;
		model.map(p.u, p.v, p.z, x, y);
		sum += (x - p.x) * (x - p.x) + (y - p.y) * (y - p.y);
	}
	return std::sqrt(sum / points.size());
}

} // namespace

TEST(CameraRig, UndistortInvertsDistort)
{
	CameraRig rig;
	rig.configure(640, 480, true, 60);
	for (const LensModel *lens : { &rig.colour(), &rig.tof() })
		for (double y = 0; y < lens->height; y += lens->height / 7.0)
			for (double x = 0; x < lens->width; x += lens->width / 9.0) {
				double xn, yn, x2, y2;
				lens->undistort(x, y, xn, yn);
				lens->distort(xn, yn, x2, y2);
				EXPECT_NEAR(x2, x, 1e-6);
				EXPECT_NEAR(y2, y, 1e-6);
			}
}

TEST(CameraRig, TofToColourAndBackAgree)
{
	CameraRig rig;
	rig.configure(640, 480, true, 60);
	for (double z : { 0.6, 1.3, 2.4 }) {
		double x, y, u, v, tofZ;
		ASSERT_TRUE(rig.tofToColour(40, 90, z, x, y));
		// The colour-frame depth of that point, then back into the ToF.
		double xn, yn;
		rig.tof().undistort(40, 90, xn, yn);
		double zColour = rig.toColour({ xn * z, yn * z, z }).z();
		ASSERT_TRUE(rig.colourToTof(x, y, zColour, u, v, tofZ));
		EXPECT_NEAR(u, 40, 1e-6);
		EXPECT_NEAR(v, 90, 1e-6);
		EXPECT_NEAR(tofZ, z, 1e-9);
	}
}

TEST(CameraRig, ParallaxShrinksWithDepthLikeTheBaseline)
{
	CameraRig rig;
	rig.configure(640, 480, false, 60);
	double xNear, yNear, xFar, yFar;
	rig.tofToColour(80, 62, 0.5, xNear, yNear);
	rig.tofToColour(80, 62, 2.5, xFar, yFar);
	// Pinholes: the shift is f * baseline * (1/0.5 - 1/2.5) = 600 * 0.06 * 1.6.
	EXPECT_NEAR(xNear - xFar, 600 * 0.06 * 1.6, 1.0);
}

// Issue 7's calibration fits algo/mapping_model.hpp's parallax model to
// measured correspondences; the true mapping must be representable by it.
TEST(CameraRig, ParallaxModelRepresentsTheTrueMappingWellUnderHalfAPixel)
{
	CameraRig rig;
	rig.configure(640, 480, true, 60);
	std::vector<Correspondence> points = sampleRig(rig);
	ASSERT_GT(points.size(), 1000u);
	double parallax = fitRms(rig, MappingKind::Parallax, points);
	double paper = fitRms(rig, MappingKind::Paper, points);
	std::printf("rig mapping fit over 0.5..2.5 m: parallax %.3f px RMS, paper %.3f px RMS\n",
		    parallax, paper);
	EXPECT_LT(parallax, 0.25);
	// The paper's model has no parallax term: it cannot follow the baseline.
	EXPECT_GT(paper, parallax * 4);
}
