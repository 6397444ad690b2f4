#include "config/file_format.hpp"

#include "config/text_file.hpp"

#include <algorithm>
#include <charconv>
#include <cstring>

namespace depthkey {

std::string checkUtcDate(std::string_view date)
{
	// Digits where digits belong, the separators fixed.
	constexpr std::string_view kPattern = "dddd-dd-ddTdd:dd:ddZ";
	bool ok = date.size() == kPattern.size();
	for (size_t i = 0; ok && i < date.size(); i++)
		ok = kPattern[i] == 'd' ? (date[i] >= '0' && date[i] <= '9') : date[i] == kPattern[i];
	return ok ? "" : "is not a UTC date like \"2024-05-01T12:00:00Z\"";
}

std::string formatExact(double value)
{
	char buf[64];
	auto result = std::to_chars(buf, buf + sizeof(buf), value);
	return std::string(buf, result.ptr);
}

int lastLineOf(std::string_view text)
{
	int lines = static_cast<int>(std::count(text.begin(), text.end(), '\n'));
	if (!text.empty() && text.back() != '\n')
		lines++;
	return std::max(lines, 1);
}

bool readToolFile(const std::string &path, const char *what, std::string &text, ConfigError &error)
{
	// Regular files only, size-capped before reading (config/text_file.hpp).
	std::string why;
	if (readTextFile(path, kMaxConfigFileBytes, text, why) < 0) {
		error = { path, 0, 0, "", std::string("cannot read ") + what + " file: " + why };
		return false;
	}
	return true;
}

} // namespace depthkey
