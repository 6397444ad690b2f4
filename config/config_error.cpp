// Formatting of config errors for the journal and for the terminal.
#include "config/config_error.hpp"

#include <algorithm>

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

void capErrors(std::vector<ConfigError> &errors, size_t omitted, const std::string &file)
{
	// Capped before (more errors may have been added after): fold it in.
	for (const ConfigError &e : errors)
		omitted += e.omitted;
	std::erase_if(errors, [](const ConfigError &e) { return e.omitted != 0; });
	// A problem with no place in the file (line 0) sorts first: it is
	// usually why everything else is wrong.
	std::stable_sort(errors.begin(), errors.end(), [](const ConfigError &a, const ConfigError &b) {
		return std::pair(a.line, a.column) < std::pair(b.line, b.column);
	});
	if (errors.size() > kMaxReportedErrors) {
		omitted += errors.size() - kMaxReportedErrors;
		errors.resize(kMaxReportedErrors);
	}
	if (omitted)
		errors.push_back({ file, 0, 0, "",
				   "and " + std::to_string(omitted) + " more error" +
					   (omitted == 1 ? "" : "s"),
				   omitted });
}

size_t countErrors(const std::vector<ConfigError> &errors)
{
	if (!errors.empty() && errors.back().omitted)
		return errors.size() - 1 + errors.back().omitted;
	return errors.size();
}

} // namespace depthkey
