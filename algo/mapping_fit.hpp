// Fitting a mapping model to measured point pairs by linear least squares.
//
// Every model is linear in its coefficients (algo/mapping_model.hpp), so the
// least-squares solution is exact and unique once the points span the model:
// the paper's steepest descent minimises the same squared error and at best
// converges to this. The regressors are MappingModel::basis(), so the fit and
// map() can never disagree.
#pragma once

#include <span>
#include <string>

#include "algo/mapping_model.hpp"
#include "algo/residual_stats.hpp"

namespace depthkey {

// One circle centre seen by both cameras.
struct PointPair {
	double u = 0, v = 0;    // ToF pixel (sub-pixel)
	double zMetres = 0;     // ToF depth at (u, v)
	double x2 = 0, y2 = 0;  // colour pixel of the same circle
};

// Fits model.kind's coefficients for model's image sizes. Returns 0, or
// -EINVAL with error saying why when the points cannot determine them (too
// few, or not spread over enough depths or image area).
int fitMapping(std::span<const PointPair> points, MappingModel &model, std::string &error);

// How far model maps each ToF point from its colour point.
ResidualStats measureResiduals(const MappingModel &model, std::span<const PointPair> points);

} // namespace depthkey
