# The installed /etc/depthkey/depthkey.toml (issue 30) is config/depthkey.toml
# with the box's real devices instead of the simulator, made by `make install`
# (and so by the package) with this script: the two cannot drift apart, and
# tests/box_config_test.cpp checks that only these three keys differ.
#   [colour] backend: a V4L2 webcam (colour.device, /dev/video0 by default)
#   [depth]  backend: the SR-2 on USB (a V4L2 Z16 camera: "v4l2", depth.device)
#   [board]  backend: a solid colour until the board is connected (docs/board.md)
# make run and the tests keep config/depthkey.toml's "sim".
/^\[colour\]$/,/^\[/ s/^backend = "sim"$/backend = "v4l2"/
/^\[depth\]$/,/^\[/ s/^backend = "sim"$/backend = "sr2"/
/^\[board\]$/,/^\[/ s/^backend = "sim"$/backend = "colour"/
