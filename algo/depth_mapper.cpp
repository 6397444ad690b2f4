#include "algo/depth_mapper.hpp"

#include <cmath>

namespace depthkey {

// round(2^32 / z) for every z, made by the compiler: read-only pages of the
// binary, of which only those of the depths seen are ever resident (a depth
// camera's 0.3-7.5 m are some 30 kB of the 256 kB), shared by every mapper.
// z = 0 is no measurement (callers never map it); z = 1 saturates.
constinit const std::array<uint32_t, 65536> DepthMapper::kReciprocal = [] {
	std::array<uint32_t, 65536> r{};
	r[1] = UINT32_MAX;
	for (uint32_t z = 2; z < 65536; ++z)
		r[z] = uint32_t(((uint64_t(1) << 32) + z / 2) / z);
	return r;
}();

void DepthMapper::configure(const MappingModel &model)
{
	tofWidth_ = model.tofWidth;
	tofHeight_ = model.tofHeight;
	colourWidth_ = model.colourWidth;
	colourHeight_ = model.colourHeight;
	terms_.resize(static_cast<size_t>(tofWidth_) * tofHeight_);
	auto q = [](double v) { return static_cast<int64_t>(std::llround(v)); };
	for (int v = 0; v < tofHeight_; ++v) {
		for (int u = 0; u < tofWidth_; ++u) {
			MappingTerms x, y;
			model.decompose(u, v, x, y);
			terms_[static_cast<size_t>(v) * tofWidth_ + u] = {
				q(x.s * 256.0), q(x.tz * 256.0 * 65536.0 / 1000.0), q(x.tinv * 1000.0 * 256.0),
				q(y.s * 256.0), q(y.tz * 256.0 * 65536.0 / 1000.0), q(y.tinv * 1000.0 * 256.0),
			};
		}
	}
}

} // namespace depthkey
