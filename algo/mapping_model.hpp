// The depth -> colour mapping of paper section 5, and a parallax variant.
//
// A ToF pixel (u, v) with depth z lands at colour pixel (x2, y2). Inputs are
// normalised so that fitted coefficients stay well conditioned:
//   x3 = (u + 0.5) * W / Wtof - 0.5        ToF column scaled to colour pixels
//   s  = (x3 - (W - 1) / 2) / (W / 2)      in about [-1, 1]   (t likewise for y)
//   z  = depth in metres
// Models (x shown; y is the same with s and t swapped and its own coefficients):
//   Identity:  x2 = x3
//   Paper:     x2 = A(s) + C(z)  = a0 + a1 s + a2 s^2 + a3 s^3 + c1 z
//              (C, D of degree 1; their constant merges into A, B's)
//   Parallax:  x2 = cubic(s, t) + (e0 + e1 s + e2 t) / z + c1 z
//              cubic = all ten monomials of degree <= 3 in s and t, so radial
//              distortion (x * r^2 couples x and y) and a tilted mount are
//              covered; 1/z is the stereo baseline's parallax.
// Every model has the form  x2 = S(u,v) + Tz(u,v) * z + Tinv(u,v) / z, which is
// what the fixed-point mapper precomputes per ToF pixel (decompose()).
#pragma once

#include <array>
#include <string_view>

namespace depthkey {

enum class MappingKind { Identity, Paper, Parallax };

const char *mappingKindName(MappingKind kind);
bool parseMappingKind(std::string_view text, MappingKind &kind);

// Per-axis coefficient layout (index into MappingModel::x / ::y):
//   Paper:    [0..3] = a0..a3 (powers of s for x, of t for y), [4] = c1 (z)
//   Parallax: [0..9] = monomials 1, s, t, s^2, s t, t^2, s^3, s^2 t, s t^2, t^3
//             (for y the same monomials, not swapped), [10..12] = e0, e1, e2
//             (1/z, s/z, t/z), [13] = c1 (z)
constexpr int kMappingCoefficients = 14;

struct MappingTerms {
	double s = 0, tz = 0, tinv = 0; // x2 = s + tz * zMetres + tinv / zMetres
};

struct MappingModel {
	MappingKind kind = MappingKind::Identity;
	int colourWidth = 640, colourHeight = 480;
	int tofWidth = 160, tofHeight = 124;
	std::array<double, kMappingCoefficients> x{};
	std::array<double, kMappingCoefficients> y{};

	// Normalised coordinates of ToF pixel (u, v); see the header comment.
	void normalise(double u, double v, double &s, double &t) const;
	// Where ToF pixel (u, v) at depth zMetres lands in the colour image.
	void map(double u, double v, double zMetres, double &x2, double &y2) const;
	// The depth-independent parts of map() for one ToF pixel.
	void decompose(double u, double v, MappingTerms &xTerms, MappingTerms &yTerms) const;

	// The regressors of one axis for a point, in coefficient order, so the
	// calibration fit and map() can never disagree. Returns how many are used.
	int basis(double s, double t, double zMetres, bool yAxis, std::array<double, kMappingCoefficients> &out) const;

	// Every field: the pipeline remaps when any differs, so a field added
	// here can never be forgotten by a hand-written comparison.
	bool operator==(const MappingModel &) const = default;
};

} // namespace depthkey
