#include "hal/recording/sequence_format.hpp"

#include <cstdio>

namespace depthkey::recording {

std::string formatTimestamp(uint64_t ns)
{
	char text[40];
	std::snprintf(text, sizeof(text), "%llu.%09llu", static_cast<unsigned long long>(ns / 1000000000u),
		      static_cast<unsigned long long>(ns % 1000000000u));
	return text;
}

// Whole seconds, a point, up to nine decimals (fewer are allowed, as other
// tools write six): parsed as integers, never through a double.
bool parseTimestamp(const std::string &text, uint64_t &ns)
{
	size_t dot = text.find('.');
	std::string whole = text.substr(0, dot);
	std::string fraction = dot == std::string::npos ? "" : text.substr(dot + 1);
	if (whole.empty() || whole.size() > 10 || fraction.size() > 9)
		return false;
	uint64_t seconds = 0, nanos = 0;
	for (char c : whole) {
		if (c < '0' || c > '9')
			return false;
		seconds = seconds * 10 + static_cast<uint64_t>(c - '0');
	}
	for (size_t i = 0; i < 9; ++i) {
		char c = i < fraction.size() ? fraction[i] : '0';
		if (c < '0' || c > '9')
			return false;
		nanos = nanos * 10 + static_cast<uint64_t>(c - '0');
	}
	ns = seconds * 1000000000u + nanos;
	return true;
}

std::string frameFileName(Stream stream, uint64_t sequence)
{
	char text[64];
	std::snprintf(text, sizeof(text), "%s/%06llu.png", kStreams[stream],
		      static_cast<unsigned long long>(sequence));
	return text;
}

} // namespace depthkey::recording
