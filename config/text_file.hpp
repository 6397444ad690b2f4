// Reading a whole file that a user or technician named, safely: it may be
// anything (a FIFO, /dev/zero, a symlink to either, a 3 GB sparse file).
#pragma once

#include <cstddef>
#include <string>

namespace depthkey {

// Configs and calibrations are a few kilobytes; 1 MiB leaves room for any
// real one and bounds both the memory and the parse time of a hostile one
// (tests/bench/config_parse_bench.cpp measures a 1 MiB config).
constexpr size_t kMaxConfigFileBytes = 1u << 20;

// Reads path into text when it is a regular file of at most maxBytes.
// Opened with O_NONBLOCK, so a FIFO or device never blocks the caller, and
// checked with fstat() on that fd (no race with a rename) before a byte is
// read. Returns 0, or a negative errno with why set to a sentence fragment
// for "cannot read FILE: <why>": "No such file or directory", "not a regular
// file (a FIFO)", "too large: 3000000000 bytes, at most 1048576".
int readTextFile(const std::string &path, size_t maxBytes, std::string &text, std::string &why);

// The kind of a non-regular file for messages: "a FIFO", "a directory"...
const char *fileKindName(unsigned int mode);

} // namespace depthkey
