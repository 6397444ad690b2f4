// Hold-out split, one fit per model, residuals per depth, model selection.
#include "algo/calibration_fit.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>

namespace depthkey {

namespace {

constexpr MappingKind kModels[] = { MappingKind::Paper, MappingKind::Parallax };

// Views are grouped by their depth to the centimetre: the technician holds
// the pattern "at 1.5 m", not at 1.4973 m.
double depthGroup(double depthM)
{
	return std::round(depthM * 100.0) / 100.0;
}

// Depths whose points determine the depth terms: the paper's constant and
// z need two, the parallax model's constant, z and 1/z need three.
size_t depthsNeeded(MappingKind kind)
{
	return kind == MappingKind::Parallax ? 3 : 2;
}

std::string ordinal(int n)
{
	int lastTwo = n % 100;
	const char *suffix = (lastTwo >= 11 && lastTwo <= 13) ? "th"
			     : n % 10 == 1                    ? "st"
			     : n % 10 == 2                    ? "nd"
			     : n % 10 == 3                    ? "rd"
							      : "th";
	return std::to_string(n) + suffix;
}

struct Split {
	std::vector<const CalibrationView *> fit, heldOut;
	std::string description;
};

Split splitViews(std::span<const CalibrationView> views, const CalibrationFitOptions &options)
{
	Split split;
	for (size_t i = 0; i < views.size(); i++) {
		bool out = options.holdOutDepthM
				   ? depthGroup(views[i].depthM) == depthGroup(*options.holdOutDepthM)
				   : options.holdOutEvery > 0 &&
					     (i + 1) % static_cast<size_t>(options.holdOutEvery) == 0;
		(out ? split.heldOut : split.fit).push_back(&views[i]);
	}
	char buf[64];
	if (options.holdOutDepthM)
		std::snprintf(buf, sizeof(buf), "views at %g m", depthGroup(*options.holdOutDepthM));
	else
		std::snprintf(buf, sizeof(buf), "every %s view", ordinal(options.holdOutEvery).c_str());
	split.description = buf;
	return split;
}

std::vector<double> depthsOf(const std::vector<const CalibrationView *> &views)
{
	std::vector<double> depths;
	for (const CalibrationView *v : views)
		depths.push_back(depthGroup(v->depthM));
	std::sort(depths.begin(), depths.end());
	depths.erase(std::unique(depths.begin(), depths.end()), depths.end());
	return depths;
}

std::vector<PointPair> pointsOf(const std::vector<const CalibrationView *> &views,
				std::optional<double> atDepth = std::nullopt)
{
	std::vector<PointPair> points;
	for (const CalibrationView *v : views)
		if (!atDepth || depthGroup(v->depthM) == *atDepth)
			points.insert(points.end(), v->points.begin(), v->points.end());
	return points;
}

// The residual rows of one model on one set, one per depth of that set.
void addResiduals(const MappingModel &model, const std::vector<const CalibrationView *> &views,
		  bool heldOut, std::vector<CalibrationResidual> &rows)
{
	for (double depth : depthsOf(views))
		rows.push_back({ model.kind, heldOut, depth,
				 measureResiduals(model, pointsOf(views, depth)) });
}

} // namespace

int fitCalibration(std::span<const CalibrationView> views, const CalibrationFitOptions &options,
		   CalibrationFit &fit, std::string &error, std::vector<std::string> &notes)
{
	fit = {};
	Split split = splitViews(views, options);
	fit.heldOutViews = split.description;
	fit.depthsM = depthsOf(split.fit);
	if (split.heldOut.empty() && !options.model) {
		error = "no view is held out (" + split.description + " of " +
			std::to_string(views.size()) +
			" views), so the models cannot be compared: take more views";
		return -EINVAL;
	}

	std::vector<PointPair> fitPoints = pointsOf(split.fit);
	std::vector<PointPair> heldOutPoints = pointsOf(split.heldOut);
	for (MappingKind kind : kModels) {
		if (options.model && *options.model != kind)
			continue;
		MappingModel model = options.sizes;
		model.kind = kind;
		std::string why;
		if (fit.depthsM.size() < depthsNeeded(kind)) {
			why = "needs views at " + std::to_string(depthsNeeded(kind)) +
			      " depths or more, has " + std::to_string(fit.depthsM.size());
		} else if (fitMapping(fitPoints, model, why) == 0) {
			fit.models.push_back(model);
			fit.summaries.push_back({ kind, measureResiduals(model, fitPoints),
						  measureResiduals(model, heldOutPoints) });
			addResiduals(model, split.fit, false, fit.residuals);
			addResiduals(model, split.heldOut, true, fit.residuals);
			continue;
		}
		notes.push_back(std::string("model ") + mappingKindName(kind) + ": " + why);
	}
	if (fit.models.empty()) {
		error = notes.empty() ? "no model could be fitted" : notes.back();
		return -EINVAL;
	}

	size_t best = 0;
	for (size_t i = 1; i < fit.models.size(); i++)
		if (fit.summaries[i].heldOut.rmsPx < fit.summaries[best].heldOut.rmsPx)
			best = i;
	fit.mapping = fit.models[best];
	fit.selectedBy = options.model ? "option" : "heldout";
	return 0;
}

} // namespace depthkey
