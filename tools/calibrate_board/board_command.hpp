// depthkey-calibrate --board: the board calibration (homography colour px ->
// board px), a mode of depthkey-calibrate of its own (tools/calibrate_board/).
#pragma once

namespace depthkey {

// True when argv asks for --board.
bool wantsBoardCalibration(int argc, char **argv);
// The whole command; returns the exit status.
int runBoardCalibration(int argc, char **argv);

} // namespace depthkey
