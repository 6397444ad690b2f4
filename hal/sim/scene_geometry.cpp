#include "hal/sim/scene_geometry.hpp"

#include <algorithm>
#include <cmath>

namespace depthkey::sim {

namespace {

// A lectern-high desk (1.0 m) at 1.05..1.35 m, right of centre, with a
// monitor on it; both lie in the lecturer's depth interval.
constexpr double kDeskLeft = 0.30, kDeskRight = 0.95;
constexpr double kDeskFront = 1.05, kDeskBack = 1.35;
constexpr double kDeskTopY = kCameraHeightM - 1.0;

Quad quad(Eigen::Vector3d origin, Eigen::Vector3d u, Eigen::Vector3d v, Rgb8 colour, float reflectivity,
	  QuadSurface surface = QuadSurface::Plain)
{
	return { origin, u, v, colour, reflectivity, surface };
}

} // namespace

std::vector<Quad> deskQuads()
{
	const double width = kDeskRight - kDeskLeft, depth = kDeskBack - kDeskFront;
	const double height = kCameraHeightM - kDeskTopY;
	return {
		// front, top, left side
		quad({ kDeskLeft, kDeskTopY, kDeskFront }, { width, 0, 0 }, { 0, height, 0 }, { 128, 92, 60 }, 0.6f),
		quad({ kDeskLeft, kDeskTopY, kDeskFront }, { width, 0, 0 }, { 0, 0, depth }, { 158, 118, 80 }, 0.6f),
		quad({ kDeskLeft, kDeskTopY, kDeskFront }, { 0, 0, depth }, { 0, height, 0 }, { 104, 74, 48 }, 0.6f),
		// monitor: a glossy black screen (weak ToF return) on a grey stand
		quad({ 0.38, -0.10, 1.22 }, { 0.34, 0, 0 }, { 0, 0.30, 0 }, { 18, 18, 22 }, 0.08f),
		quad({ 0.53, 0.20, 1.24 }, { 0.04, 0, 0 }, { 0, kDeskTopY - 0.20, 0 }, { 90, 90, 96 }, 0.4f),
	};
}

StaticScene StaticScene::build(double boardDistanceM, bool desk, const CalibrationTarget *target)
{
	StaticScene scene;
	scene.target = target;
	if (target) {
		double w = (target->columns - 1) * target->spacingM + 2 * target->marginM + target->diameterM;
		double h = (target->rows - 1) * target->spacingM + 2 * target->marginM + target->diameterM;
		Eigen::Vector3d ax = target->rotation.col(0), ay = target->rotation.col(1);
		scene.quads.push_back(quad(target->centre - ax * (w / 2) - ay * (h / 2), ax * w, ay * h,
					   { 240, 240, 236 }, 0.9f, QuadSurface::CalibrationTarget));
	}
	if (desk)
		for (const Quad &q : deskQuads())
			scene.quads.push_back(q);
	// The board plane with the wall around its display area: big enough to
	// fill both cameras' views.
	scene.quads.push_back(quad({ -8, -8, boardDistanceM }, { 16, 0, 0 }, { 0, 16, 0 }, { 186, 180, 166 },
				   0.8f, QuadSurface::Board));
	return scene;
}

void calibrationTargetSurface(const CalibrationTarget &target, double s, double t, double footprintM,
			      Rgb8 &colour, float &reflectivity)
{
	double w = (target.columns - 1) * target.spacingM + 2 * target.marginM + target.diameterM;
	double h = (target.rows - 1) * target.spacingM + 2 * target.marginM + target.diameterM;
	// Position relative to the first circle's centre, in metres.
	double px = s * w - target.marginM - target.diameterM / 2;
	double py = t * h - target.marginM - target.diameterM / 2;
	int i = std::clamp(static_cast<int>(std::lround(px / target.spacingM)), 0, target.columns - 1);
	int j = std::clamp(static_cast<int>(std::lround(py / target.spacingM)), 0, target.rows - 1);
	double dist = std::hypot(px - i * target.spacingM, py - j * target.spacingM);
	// Share of the footprint inside the circle (linear ramp over one footprint).
	double black = std::clamp((target.diameterM / 2 - dist) / std::max(footprintM, 1e-5) + 0.5, 0.0, 1.0);
	auto mix = [black](double white, double dark) { return white + (dark - white) * black; };
	uint8_t level = static_cast<uint8_t>(std::lround(mix(240, 22)));
	colour = { level, level, static_cast<uint8_t>(std::lround(mix(236, 22))) };
	reflectivity = static_cast<float>(mix(0.9, 0.05));
}

} // namespace depthkey::sim
