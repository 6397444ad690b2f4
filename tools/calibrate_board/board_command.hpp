// depthkey-calibrate --board: the board calibration (homography colour px ->
// board px), a mode of depthkey-calibrate of its own (tools/calibrate_board/).
#pragma once

#include "config/board_calibration_file.hpp"

#include <cstdint>
#include <cstdio>
#include <string>

namespace depthkey {

// Parses "WxH" (either x), each side at least 16 and at most maxW / maxH.
bool parseSize(const char *text, int &w, int &h, int maxW, int maxH);
// The --board forms' usage lines (each indented as a continuation of
// "usage:"), for depthkey-calibrate --help and --board --help.
void printBoardUsage(FILE *out);
// True when argv asks for --board.
bool wantsBoardCalibration(int argc, char **argv);
// The whole command; returns the exit status.
int runBoardCalibration(int argc, char **argv);
// What --board --sim fits (the simulated display showing the pattern, seen by
// the seed's colour camera with its lens), for depthkey-calibrate --sim to
// keep in the calibration file's [board]: the simulated room calibrated in
// one go. 0, or a negative errno with error saying why.
int fitSimBoardCalibration(uint64_t seed, int colourWidth, int colourHeight, int boardWidth, BoardCalibration &out,
			   std::string &error);

} // namespace depthkey
