// The one place that turns the settings into the pipeline's and the frame
// pairer's configuration, so that depthkeyd and depthkey-eval can never run
// them differently.
#pragma once

#include "algo/frame_pairer.hpp"
#include "algo/pipeline.hpp"
#include "config/settings.hpp"

namespace depthkey {

inline void configurePipeline(Pipeline &pipeline, const Settings &settings)
{
	pipeline.configure(settings.segmentation, settings.composite);
}

inline void configurePairer(FramePairer &pairer, const Settings &settings)
{
	pairer.configure(int64_t{ settings.pairing.offsetMs } * 1'000'000,
			 uint64_t(settings.pairing.maxSkewMs) * 1'000'000);
}

} // namespace depthkey
