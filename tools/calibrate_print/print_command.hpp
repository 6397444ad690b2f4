// depthkey-calibrate --print-pattern FILE: the depth calibration pattern
// (algo/printed_pattern.hpp) as a PDF or SVG at its true size, through cairo,
// for the technician to print at 100 %.
#pragma once

#include <cstdio>

namespace depthkey {

// True when argv asks for --print-pattern.
bool wantsPatternPrint(int argc, char **argv);
// The whole command; returns the exit status.
int runPatternPrint(int argc, char **argv);
// Its usage line(s), for depthkey-calibrate --help.
void printPatternUsage(FILE *out);

} // namespace depthkey
