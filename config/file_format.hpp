// What the files the tools write (the depth calibration, the board
// calibration) share: their date format, numbers that read back bit for bit,
// where a file cut short is reported, and reading them with an error that
// names the file.
#pragma once

#include "config/config_error.hpp"

#include <string>
#include <string_view>

namespace depthkey {

// "" for a UTC date like "2024-05-01T12:00:00Z", else why not.
std::string checkUtcDate(std::string_view date);
// The shortest text that reads back as the same double.
std::string formatExact(double value);
// The last line of text (1 for an empty one): where a problem with no place
// in the text is reported, which is where a file cut short stops.
int lastLineOf(std::string_view text);
// Reads path into text; on failure an error naming the file ("cannot open
// <what> file: ...") at line 0 and false.
bool readToolFile(const std::string &path, const char *what, std::string &text, ConfigError &error);

} // namespace depthkey
