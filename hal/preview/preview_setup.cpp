#include "hal/preview/preview_setup.hpp"

#include <nlohmann/json.hpp>

namespace depthkey {

namespace {

nlohmann::json calibrationJson(const PreviewSetupCalibration &c)
{
	return { { "calibrated", c.calibrated }, { "file", c.file }, { "state", c.state }, { "next", c.next } };
}

} // namespace

nlohmann::json previewSetupJson(const PreviewSetup &setup)
{
	nlohmann::json devices = nlohmann::json::array();
	for (const PreviewSetupDevice &d : setup.devices)
		devices.push_back({ { "role", d.role },
				    { "backend", d.backend },
				    { "device", d.device },
				    { "found", d.found },
				    { "name", d.name },
				    { "next", d.next } });
	return { { "ready", setup.next.empty() },
		 { "next", setup.next },
		 { "devices", devices },
		 { "depth_calibration", calibrationJson(setup.depth) },
		 { "board_calibration", calibrationJson(setup.board) } };
}

} // namespace depthkey
