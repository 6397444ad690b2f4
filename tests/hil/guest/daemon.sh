# The real depthkeyd against the virtual devices (sourced by main.sh).
# Needs the SR-2, V4L2 and gpiod backends: until they are built in, the
# daemon checks are reported as skipped, with the reason.
if ! "$HIL_BIN/depthkeyd" --help 2>&1 | grep -q sr2 &&
	! grep -q '"sr2"' "$here/../../../config/config_loader.cpp" 2>/dev/null; then
	hil_skip daemon "depthkeyd has no sr2/v4l2/gpiod backends yet"
	return 0
fi
