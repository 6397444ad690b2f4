// A whole calibration from the views of the pattern: hold some views out,
// fit every model on the rest, measure each on both sets per depth, and pick
// the model that predicts the held-out views best.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <vector>

#include "algo/mapping_fit.hpp"

namespace depthkey {

// The pattern at one pose: its circle centres seen by both cameras.
struct CalibrationView {
	double depthM = 0;      // the depth it was held at; views are grouped by it (to 1 cm)
	std::vector<PointPair> points;
};

// One model's residuals on the views it was fitted on and on the held-out ones.
struct CalibrationSummary {
	MappingKind model = MappingKind::Parallax;
	ResidualStats fit;
	ResidualStats heldOut;
};

// One model's residuals at one depth, on the fitted or the held-out views.
struct CalibrationResidual {
	MappingKind model = MappingKind::Parallax;
	bool heldOut = false;
	double depthM = 0;
	ResidualStats stats;
};

struct CalibrationFitOptions {
	MappingModel sizes;                     // image sizes; kind and coefficients ignored
	// Which views are held out: those at holdOutDepthM when set, else every
	// holdOutEvery-th view (the 4th, 8th...).
	int holdOutEvery = 4;
	std::optional<double> holdOutDepthM;
	std::optional<MappingKind> model;       // use this model whatever the held-out error
};

struct CalibrationFit {
	MappingModel mapping;                   // the selected model
	std::string selectedBy;                 // "heldout" or "option"
	std::string heldOutViews;               // "every 4th view", "views at 1.5 m"
	std::vector<double> depthsM;            // depths of the fitted views, ascending
	std::vector<MappingModel> models;       // every model that could be fitted
	std::vector<CalibrationSummary> summaries;      // same order as models
	std::vector<CalibrationResidual> residuals;     // per model, set, depth
};

// Fits the paper and the parallax models. Returns 0, or -EINVAL with error
// saying what the views lack (held-out views, depths, points). A model the
// views cannot determine is left out with its reason in notes.
int fitCalibration(std::span<const CalibrationView> views, const CalibrationFitOptions &options,
		   CalibrationFit &fit, std::string &error, std::vector<std::string> &notes);

} // namespace depthkey
