#include "algo/calibration_plan.hpp"

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

} // namespace depthkey
