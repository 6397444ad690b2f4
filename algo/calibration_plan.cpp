#include "algo/calibration_plan.hpp"

#include <algorithm>

namespace depthkey {

std::string PatternStep::where() const
{
	if (across == 0 && down == 0)
		return "middle";
	std::string vertical = down < 0 ? "top" : down > 0 ? "bottom" : "";
	std::string horizontal = across < 0 ? "left" : across > 0 ? "right" : "";
	if (vertical.empty() || horizontal.empty())
		return vertical + horizontal;
	return vertical + " " + horizontal;
}

std::vector<double> defaultCalibrationDepths()
{
	return { 0.9, 1.2, 1.6, 2.0, 2.5 };
}

std::vector<PatternStep> calibrationPlan(const std::vector<double> &depthsM)
{
	constexpr int kPlaces[][2] = { { 0, 0 }, { -1, -1 }, { 1, -1 }, { -1, 1 }, { 1, 1 } };
	std::vector<PatternStep> steps;
	for (double depth : depthsM)
		for (const auto &place : kPlaces)
			steps.push_back({ depth, place[0], place[1] });
	return steps;
}

int farSurfaceMm(const Gray16Image &depthMm)
{
	std::vector<uint16_t> measured;
	measured.reserve(depthMm.size());
	for (int y = 0; y < depthMm.height(); ++y)
		for (int x = 0; x < depthMm.width(); ++x)
			if (const uint16_t d = depthMm.row(y)[x])
				measured.push_back(d);
	if (measured.empty() || measured.size() * 10 < depthMm.size())
		return 0;
	const auto at = measured.begin() + std::ptrdiff_t(measured.size() * 3 / 4);
	std::nth_element(measured.begin(), at, measured.end());
	return *at;
}

std::vector<double> depthsInFrontOf(const std::vector<double> &depthsM, double surfaceM, double clearanceM)
{
	std::vector<double> kept;
	for (double depth : depthsM)
		if (depth <= surfaceM - clearanceM)
			kept.push_back(depth);
	return kept;
}

} // namespace depthkey
