// libFuzzer harness: the daemon's config loader (TOML -> Settings) on any
// bytes. Invariants: no crash, no sanitizer report, at most 20 errors plus
// the closing "and N more" entry, and every error names the file.
#include "config/config_loader.hpp"

#include <cstdlib>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	std::string_view text(reinterpret_cast<const char *>(data), size);
	depthkey::ConfigResult result = depthkey::parseConfig(text, "fuzz.toml");
	if (result.errors.size() > depthkey::kMaxReportedErrors + 1)
		std::abort();
	for (const depthkey::ConfigError &e : result.errors)
		if (e.file != "fuzz.toml" || e.toString().empty())
			std::abort();
	return 0;
}
