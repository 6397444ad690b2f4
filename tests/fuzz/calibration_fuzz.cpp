// libFuzzer harness: the calibration file reader. Invariant beyond "no
// crash": a calibration it accepts is written back (formatCalibration) to a
// text it accepts again with the same mapping, the writer's promise.
#include "config/calibration_file.hpp"

#include <cstdlib>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	using namespace depthkey;
	std::string_view text(reinterpret_cast<const char *>(data), size);
	CalibrationResult result = parseCalibration(text, "fuzz.toml");
	if (result.errors.size() > kMaxReportedErrors + 1)
		std::abort();
	if (!result.ok())
		return 0;
	CalibrationResult again = parseCalibration(formatCalibration(result.calibration), "again.toml");
	if (!again.ok() || again.calibration.mapping.x != result.calibration.mapping.x ||
	    again.calibration.mapping.y != result.calibration.mapping.y)
		std::abort();
	return 0;
}
