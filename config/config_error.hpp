// One problem found in a config file, located precisely enough for a
// technician to fix it without reading the loader's source.
#pragma once

#include <string>

namespace depthkey {

struct ConfigError {
	std::string file;
	int line = 0;           // 1-based; 0 when the problem has no place in the file
	int column = 0;         // 1-based
	std::string key;        // dotted, e.g. "segmentation.near_mm"; "" for syntax errors
	std::string message;

	// "FILE:LINE:COLUMN: KEY: MESSAGE", the compiler-style form editors can
	// jump to. Parts that are unknown (no line, no key) are left out.
	std::string toString() const;

	bool operator==(const ConfigError &) const = default;
};

} // namespace depthkey
