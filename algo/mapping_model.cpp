#include "algo/mapping_model.hpp"

namespace depthkey {

const char *mappingKindName(MappingKind kind)
{
	switch (kind) {
	case MappingKind::Identity:
		return "identity";
	case MappingKind::Paper:
		return "paper";
	case MappingKind::Parallax:
		return "parallax";
	}
	return "?";
}

bool parseMappingKind(std::string_view text, MappingKind &kind)
{
	for (MappingKind k : { MappingKind::Identity, MappingKind::Paper, MappingKind::Parallax }) {
		if (text == mappingKindName(k)) {
			kind = k;
			return true;
		}
	}
	return false;
}

void MappingModel::normalise(double u, double v, double &s, double &t) const
{
	double x3 = (u + 0.5) * colourWidth / tofWidth - 0.5;
	double y3 = (v + 0.5) * colourHeight / tofHeight - 0.5;
	s = (x3 - (colourWidth - 1) / 2.0) / (colourWidth / 2.0);
	t = (y3 - (colourHeight - 1) / 2.0) / (colourHeight / 2.0);
}

int MappingModel::basis(double s, double t, double zMetres, bool yAxis,
			std::array<double, kMappingCoefficients> &out) const
{
	out.fill(0.0);
	switch (kind) {
	case MappingKind::Identity:
		return 0;
	case MappingKind::Paper: {
		double p = yAxis ? t : s;
		out[0] = 1.0;
		out[1] = p;
		out[2] = p * p;
		out[3] = p * p * p;
		out[4] = zMetres;
		return 5;
	}
	case MappingKind::Parallax: {
		double inv = 1.0 / zMetres;
		out = { 1.0, s, t, s * s, s * t, t * t, s * s * s, s * s * t, s * t * t, t * t * t,
			inv, s * inv, t * inv, zMetres };
		return kMappingCoefficients;
	}
	}
	return 0;
}

void MappingModel::decompose(double u, double v, MappingTerms &xTerms, MappingTerms &yTerms) const
{
	double s, t;
	normalise(u, v, s, t);
	if (kind == MappingKind::Identity) {
		xTerms = { (u + 0.5) * colourWidth / tofWidth - 0.5, 0, 0 };
		yTerms = { (v + 0.5) * colourHeight / tofHeight - 0.5, 0, 0 };
		return;
	}
	// Evaluate the basis at z = 1 m to separate the parts: the basis is linear
	// in the terms {1, z, 1/z}, and only the last regressors carry z or 1/z.
	std::array<double, kMappingCoefficients> b;
	for (int axis = 0; axis < 2; ++axis) {
		const auto &c = axis ? y : x;
		MappingTerms &terms = axis ? yTerms : xTerms;
		int n = basis(s, t, 1.0, axis == 1, b);
		terms = {};
		if (kind == MappingKind::Paper) {
			for (int i = 0; i < 4; ++i)
				terms.s += c[i] * b[i];
			terms.tz = c[4];
		} else {
			for (int i = 0; i < 10; ++i)
				terms.s += c[i] * b[i];
			for (int i = 10; i < 13; ++i)
				terms.tinv += c[i] * b[i];
			terms.tz = c[13];
		}
		(void)n;
	}
}

void MappingModel::map(double u, double v, double zMetres, double &x2, double &y2) const
{
	MappingTerms tx, ty;
	decompose(u, v, tx, ty);
	x2 = tx.s + tx.tz * zMetres + tx.tinv / zMetres;
	y2 = ty.s + ty.tz * zMetres + ty.tinv / zMetres;
}

} // namespace depthkey
