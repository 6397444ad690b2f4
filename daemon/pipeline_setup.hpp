// The one place that turns the settings into the pipeline's configuration,
// so that depthkeyd and depthkey-eval can never run it differently.
#pragma once

#include "algo/pipeline.hpp"
#include "config/settings.hpp"

namespace depthkey {

inline void configurePipeline(Pipeline &pipeline, const Settings &settings)
{
	pipeline.configure(settings.segmentation, settings.composite);
}

} // namespace depthkey
