// Formatting of config errors for the journal and for the terminal.
#include "config/config_error.hpp"

namespace depthkey {

std::string ConfigError::toString() const
{
	std::string out = file;
	if (line > 0)
		out += ':' + std::to_string(line) + ':' + std::to_string(column);
	out += ": ";
	if (!key.empty())
		out += key + ": ";
	out += message;
	return out;
}

} // namespace depthkey
