#include "algo/depth_mapper.hpp"

#include <cmath>

namespace depthkey {

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
