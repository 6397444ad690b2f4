#!/bin/sh
# Live against offline (issue 29): the simulated lecture's seed SEED, SECONDS
# long at WIDTHxHEIGHT and FPS, scored by depthkey-eval (offline: every frame
# keyed, however long it takes) and by depthkeyd replaying the same frames
# in real time under PERCENT % of one core (cpu_share.sh): the live score the
# student would have seen on a box that slow. The replay is what the daemon
# receives; the simulator renders it beforehand, outside the share.
# Everything the box does counts against the share; what stands in for its
# camera does not: a camera delivers raw frames by DMA, while here the
# daemon decodes the recorded PNGs (its thread dk-replay) and renders the
# simulated board (threads dk-sim*). Those threads are moved out of the
# share as they appear (cpu_share.sh release: cgroup v1 only; under cgroup
# v2 without threaded mode the whole process stays in, and the line says so).
# PERCENT may be a list ("100 50 35"): one offline run, a live run each.
#
#   sh live_vs_offline.sh BIN SEED PERCENT WIDTH HEIGHT FPS SECONDS
#   sh live_vs_offline.sh --table BIN SECONDS   seeds 1-3 at 100/50/35 %, 640x480 25 fps and 1280x720 30 fps
#
# One line per run, for scripts and the process test:
#   live seed=1 share=35 size=640x480 fps=25 frames=1500 offline_iou=0.962 offline_bf=0.850
#        live_iou=0.955 live_bf=0.830 live_frames=1480 board_only=0 shed=12 keying_ms=31.0
#        outside=dk-replay
# Exit status 77 (with the reason) when no CPU share can be made here.
set -eu

here=$(cd "$(dirname "$0")" && pwd)

fail() {
	echo "live_vs_offline.sh: $*" >&2
	exit 1
}

if [ "${1:-}" = --table ]; then
	[ $# = 3 ] || fail "usage: live_vs_offline.sh --table BIN SECONDS"
	for size in "640 480 25" "1280 720 30"; do
		for seed in 1 2 3; do
			# shellcheck disable=SC2086 # size is three words on purpose
			sh "$0" "$2" "$seed" "100 50 35" $size "$3"
		done
	done
	exit 0
fi

[ $# = 7 ] || fail "usage: live_vs_offline.sh BIN SEED PERCENT WIDTH HEIGHT FPS SECONDS"
bin=$1 seed=$2 percents=$3 width=$4 height=$5 fps=$6 seconds=$7
frames=$((seconds * fps))
work=$(mktemp -d "${TMPDIR:-/tmp}/depthkey-live.XXXXXX")
daemon='' share=''
cleanup() {
	[ -z "$daemon" ] || kill "$daemon" 2>/dev/null || true
	[ -z "$share" ] || sh "$here/cpu_share.sh" remove "$share" || true
	rm -rf "$work"
}
trap cleanup EXIT INT TERM

# Where no share can be made there is nothing to measure: say so first.
probe=$(sh "$here/cpu_share.sh" create "depthkey-live-$$" 100) || exit $?
sh "$here/cpu_share.sh" remove "$probe"

"$bin/depthkey-calibrate" --sim --sim-colour-size "${width}x$height" --output "$work/calibration.toml" \
	> "$work/calibrate.log" 2>&1 || { cat "$work/calibrate.log" >&2; fail "depthkey-calibrate failed"; }
cat > "$work/sim.toml" <<TOML
[colour]
width = $width
height = $height
fps = $fps
[mapping]
calibration_file = "$work/calibration.toml"
[sim]
seed = $seed
TOML
"$bin/depthkey-eval" --config "$work/sim.toml" --sim "$seed" --frames "$frames" --save-sequence "$work/seq" \
	> "$work/eval.log" 2>&1 || { cat "$work/eval.log" >&2; fail "depthkey-eval failed"; }
offline=$(tail -n 1 "$work/eval.log")
offline_iou=$(echo "$offline" | sed -n 's/.* iou=\([0-9.]*\).*/\1/p')
offline_bf=$(echo "$offline" | sed -n 's/.* bf=\([0-9.]*\).*/\1/p')

# The daemon on the saved frames, replayed as recorded, its outputs named
# for this run (other daemons may be running), no preview page.
sed -e '/^\[colour\]$/a backend = "replay"' "$work/sim.toml" > "$work/replay.toml"
cat >> "$work/replay.toml" <<TOML
[depth]
backend = "replay"
[replay]
path = "$work/seq"
realtime = true
loop = false
[output]
composite_name = "/depthkey-live-$$.composite"
lecturer_name = "/depthkey-live-$$.lecturer"
board_lecturer_name = "/depthkey-live-$$.lecturer.board"
[preview]
listen = ""
TOML
for percent in $percents; do
	share=$(sh "$here/cpu_share.sh" create "depthkey-live-$$-$percent" "$percent")
	# Moved into the share before it becomes depthkeyd: all its work counts.
	sh -c 'echo $$ > "$1/cgroup.procs" && exec "$2/depthkeyd" --config "$3"' sh "$share" "$bin" "$work/replay.toml" \
		2> "$work/daemon.log" &
	daemon=$!
	# The replay plays once: the status line (logged every 5 s) after its
	# end scores exactly the frames depthkey-eval scored, those published.
	# Meanwhile the camera's stand-in leaves the share, its threads moved
	# out as they appear (at the start, or later: a restarted replay).
	outside='' release=1
	deadline=$(($(date +%s) + seconds + 7))
	while [ "$(date +%s)" -lt "$deadline" ]; do
		if [ "$release" = 1 ]; then
			status=0
			moved=$(sh "$here/cpu_share.sh" release "$share" "$daemon" dk-replay dk-sim) || status=$?
			case $status in
			0) ;;
			77) release=0 outside="none(cgroup-v2)" ;; # the reason is on stderr
			*) fail "cannot move the camera's stand-in out of the share" ;;
			esac
			for name in $(echo "$moved" | cut -s -d' ' -f2); do
				case ",$outside," in *",$name,"*) ;; *) outside=${outside:+$outside,}$name ;; esac
			done
		fi
		sleep 0.5
	done
	kill "$daemon"
	wait "$daemon" || true
	daemon=
	line=$(grep 'live IoU' "$work/daemon.log" | tail -n 1) || { cat "$work/daemon.log" >&2; fail "no live score logged"; }
	# "...; live IoU 0.962 BF 0.850 (5 s), 0.958 0.847 over 1480 frames, 0 board-only"
	live_iou=$(echo "$line" | sed -n 's/.*live IoU [0-9.]* BF [0-9.]* (5 s), \([0-9.]*\) .*/\1/p')
	live_bf=$(echo "$line" | sed -n 's/.*live IoU [0-9.]* BF [0-9.]* (5 s), [0-9.]* \([0-9.]*\) over.*/\1/p')
	live_frames=$(echo "$line" | sed -n 's/.* over \([0-9]*\) frames.*/\1/p')
	board_only=$(echo "$line" | sed -n 's/.* \([0-9]*\) board-only.*/\1/p')
	shed=$(echo "$line" | sed -n 's/.* \([0-9]*\) shed;.*/\1/p')
	keying=$(echo "$line" | sed -n 's/.*keying \([0-9.]*\) ms.*/\1/p')
	echo "live seed=$seed share=$percent size=${width}x$height fps=$fps frames=$frames offline_iou=$offline_iou" \
		"offline_bf=$offline_bf live_iou=$live_iou live_bf=$live_bf live_frames=$live_frames board_only=$board_only" \
		"shed=$shed keying_ms=$keying outside=${outside:-none}"
	sh "$here/cpu_share.sh" remove "$share"
	share=
done
