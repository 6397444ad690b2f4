// The normal equations would square the condition number; a column-pivoting
// QR solves the same problem stably and tells the rank.
#include "algo/mapping_fit.hpp"

#include <cerrno>

#include <Eigen/Dense>

namespace depthkey {

int fitMapping(std::span<const PointPair> points, MappingModel &model, std::string &error)
{
	std::array<double, kMappingCoefficients> row;
	int n = model.basis(0.0, 0.0, 1.0, false, row);
	if (n == 0) {
		error = std::string("model ") + mappingKindName(model.kind) + " has nothing to fit";
		return -EINVAL;
	}
	// Twice as many equations as unknowns at the very least, so one bad
	// point cannot be fitted exactly.
	if (points.size() < static_cast<size_t>(2 * n)) {
		error = std::to_string(points.size()) + " points cannot fit the " +
			std::to_string(n) + " coefficients per axis of model " +
			mappingKindName(model.kind);
		return -EINVAL;
	}

	Eigen::Index rows = static_cast<Eigen::Index>(points.size());
	for (int axis = 0; axis < 2; axis++) {
		Eigen::MatrixXd a(rows, n);
		Eigen::VectorXd b(rows);
		for (Eigen::Index i = 0; i < rows; i++) {
			const PointPair &p = points[static_cast<size_t>(i)];
			double s, t;
			model.normalise(p.u, p.v, s, t);
			model.basis(s, t, p.zMetres, axis == 1, row);
			for (int j = 0; j < n; j++)
				a(i, j) = row[j];
			b(i) = axis ? p.y2 : p.x2;
		}

		Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(a);
		if (qr.rank() < n) {
			error = "the points determine only " + std::to_string(qr.rank()) + " of the " +
				std::to_string(n) + " coefficients of model " +
				mappingKindName(model.kind) +
				": views must cover more depths and more of the image";
			return -EINVAL;
		}
		Eigen::VectorXd c = qr.solve(b);
		auto &out = axis ? model.y : model.x;
		out.fill(0.0);
		for (int j = 0; j < n; j++)
			out[j] = c(j);
	}
	return 0;
}

ResidualStats measureResiduals(const MappingModel &model, std::span<const PointPair> points)
{
	ResidualAccumulator acc;
	for (const PointPair &p : points) {
		double x, y;
		model.map(p.u, p.v, p.zMetres, x, y);
		acc.add(x - p.x2, y - p.y2);
	}
	return acc.stats();
}

} // namespace depthkey
