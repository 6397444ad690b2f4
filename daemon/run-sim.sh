#!/bin/sh
# `make run`: starts depthkeyd in the foreground on the simulated devices,
# after saying once how to look at what it produces.
#
#   sh daemon/run-sim.sh BIN BUILD [CONFIG]
#
# The daemon runs with CONFIG (default config/depthkey.toml) except for
# [mapping] calibration_file, which names BUILD/sim-calibration.toml, the
# calibration `make` fits to the simulator with depthkey-calibrate --sim, and
# [board] homography_file, which names BUILD/sim-board.toml, the board
# calibration `make` fits with depthkey-calibrate --board --sim (so that the
# composite is in the simulated board's geometry: the paper's Figure 1). The
# merged config is written to BUILD/run.toml (rewritten by every run); the
# shipped default config keeps both "".
# With RUN_SIM_PREPARE_ONLY=1 it only writes BUILD/run.toml and prints its
# path (for the tests).
set -eu
bin=$1
build=$2
source=${3:-config/depthkey.toml}
snapshots=${TMPDIR:-/tmp}/depthkey-snapshots

fail() {
	echo "run-sim.sh: $*" >&2
	exit 1
}

# The config loader wants an absolute calibration path.
build=$(cd "$build" && pwd) || fail "build folder $2 not found"
calibration=$build/sim-calibration.toml
config=$build/run.toml
[ -r "$calibration" ] ||
	fail "$calibration is missing: make run fits it ($bin/depthkey-calibrate --sim --output $calibration)"
# The path goes into a sed replacement and a TOML string: refuse what either
# would read as more than characters.
case $calibration in
*[\"\\\|\&]*) fail "cannot write the path $calibration into $config (it has \", \\, | or &)" ;;
esac
[ "$(grep -c '^calibration_file = ""$' "$source")" = 1 ] ||
	fail "$source: expected exactly one line 'calibration_file = \"\"' to point at $calibration"
board=$build/sim-board.toml # the same folder: its path passed the check above
[ -r "$board" ] ||
	fail "$board is missing: make run fits it ($bin/depthkey-calibrate --board --sim --output $board)"
[ "$(grep -c '^homography_file = ""$' "$source")" = 1 ] ||
	fail "$source: expected exactly one line 'homography_file = \"\"' to point at $board"
sed -e "s|^calibration_file = \"\"\$|calibration_file = \"$calibration\"|" \
    -e "s|^homography_file = \"\"\$|homography_file = \"$board\"|" "$source" > "$config.tmp"
mv "$config.tmp" "$config"

if [ "${RUN_SIM_PREPARE_ONLY:-0}" = 1 ]; then
	echo "$config"
	exit 0
fi

# The preview page's address, from [preview] listen ("" = off), and the
# signal commands for this daemon alone: the script execs depthkeyd, so its
# PID is this shell's ($$), whatever other depthkeyd runs on the machine.
listen=$(awk '/^\[/ { section = $0 } section == "[preview]" && /^listen *=/ {
	sub(/^listen *= *"/, ""); sub(/".*$/, ""); print; exit }' "$config")
case $listen in
"") preview="the preview page is off ([preview] listen = \"\")" ;;
0.0.0.0:*) preview="the preview page: http://127.0.0.1:${listen#0.0.0.0:}/ (and this machine's other addresses)" ;;
*) preview="the preview page: http://$listen/ (open it in a browser)" ;;
esac
pid=$$

cat <<MSG
depthkeyd is starting on simulated cameras with config $config:
$source with [mapping] calibration_file = "$calibration"
and [board] homography_file = "$board"
(both fitted to the simulator; make run writes $config afresh from $source each time).
The composite is in the board's geometry: the simulated board's slide and strokes,
the lecturer laid over them half transparent.
Look at $preview.
Look at its output from another terminal:
  $bin/depthkey-shmcat --frames 250 --yuv420 | ffmpeg -y -i - -pix_fmt yuv420p composite.mp4   # 250 frames, H.264 4:2:0, real time
  $bin/depthkey-shmcat --stream lecturer --frames 1 | ffmpeg -y -i - lecturer.png
  kill -USR1 $pid    # stage snapshots (PNG) into $snapshots; this daemon only (PID $pid)
  kill -HUP $pid     # re-read $config (edit that file, not $source, for it)
Status lines below (every 5 s); each ends with the live score, what the student sees
against the simulator's truth: "live IoU . BF . (5 s), . . over N frames" (IoU and
boundary F at 2 px of the lecturer layer, over the last 5 s and since the start,
as depthkey-eval scores them), and the frames that showed the board alone.
Ctrl-C stops it.
MSG
exec "$bin/depthkeyd" --config "$config" --snapshot-dir "$snapshots"
