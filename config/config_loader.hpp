// The daemon's config file: TOML in, Settings out, every problem reported.
//
// Loading never throws and never stops at the first problem, so a
// technician sees every mistake in one go. Keys the file leaves out keep the
// defaults in settings.hpp; keys the schema does not know are errors, so a
// typo cannot silently fall back to a default.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "config/config_error.hpp"
#include "settings/settings.hpp"

namespace depthkey {

class TomlSection;

struct ConfigResult {
	Settings settings;              // meaningful only when ok()
	std::vector<ConfigError> errors;        // in file order
	bool ok() const { return errors.empty(); }
};

// A missing or unreadable file is an error naming the file.
ConfigResult loadConfig(const std::string &path);

// The config a program uses without --config: /etc/depthkey/depthkey.toml
// on an installed box, else config/depthkey.toml of the source tree the
// running binary (build/bin/ or build/san/bin/) was built in.
std::string findDefaultConfig();

// sourceName is the file name the errors carry.
ConfigResult parseConfig(std::string_view text, const std::string &sourceName);

// The depthkey schema: which key binds to which field, with its limits.
// Exposed for tests and tools that bind with the TomlBinder directly.
void bindSettings(TomlSection &root, Settings &settings);

} // namespace depthkey
