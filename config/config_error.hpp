// One problem found in a config file, located precisely enough for a
// technician to fix it without reading the loader's source.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace depthkey {

// A file with 200,000 mistakes must not produce 200,000 journal lines (nor
// hold their text in memory): the first ones in file order are reported,
// then one line "and N more errors".
constexpr size_t kMaxReportedErrors = 20;

struct ConfigError {
	std::string file;
	int line = 0;           // 1-based; 0 when the problem has no place in the file
	int column = 0;         // 1-based
	std::string key;        // dotted, e.g. "segmentation.near_mm"; "" for syntax errors
	std::string message;
	size_t omitted = 0;     // on the closing "and N more errors" entry: N

	// "FILE:LINE:COLUMN: KEY: MESSAGE", the compiler-style form editors can
	// jump to. Parts that are unknown (no line, no key) are left out.
	std::string toString() const;

	bool operator==(const ConfigError &) const = default;
};

// Sorts errors into file order and keeps the first kMaxReportedErrors; the
// rest, with `omitted` dropped earlier, become one closing entry for file.
void capErrors(std::vector<ConfigError> &errors, size_t omitted, const std::string &file);

// How many problems errors stands for, counting those capErrors() dropped.
size_t countErrors(const std::vector<ConfigError> &errors);

} // namespace depthkey
