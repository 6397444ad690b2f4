# The real depthkeyd against the virtual devices (sourced by main.sh): the
# V4L2 backend on vivid, the SR-2 backend on the emulated camera, the gpiod
# LEDs on gpio-sim. Asserts frames flow, then injects each fault and checks
# that the daemon keeps running and publishing frames marked offline, shows
# it on the LEDs, and recovers within 2 s of the device's return; finally 50
# unplug/replug cycles must not leak file descriptors or memory. The board
# is a second vivid instance as the capture stick, in board geometry (its
# unplug and return: the "board" section).

DK_CONFIG=/run/hil-depthkey.toml
DK_LOG=$HIL_LOGS/depthkeyd.log
RECOVERY_LOG=$VM_RESULTS/recovery
RECOVERY_LIMIT_MS=2000
# HIL_SANITIZER=1: the binaries are the sanitizer build, several times slower
# under TCG and holding freed memory in ASan's quarantine: recovery times and
# VmRSS are then reported as skipped; recovery itself is still asserted.
HIL_SANITIZER=${HIL_SANITIZER:-0}
# Shared-memory flags (hal/depthkey_shm.h).
ONLINE=0x7 COLOUR_OK=0x2 DEPTH_OK=0x4
# LED lines on the simulated chip (the legend in docs/devices.md).
LED_POWER=0 LED_DEPTH=1 LED_COLOUR=2 LED_CALIBRATION=3 LED_READER=4 LED_ERROR=5 LED_BOARD=6

cat >"$DK_CONFIG" <<TOML
[colour]
backend = "v4l2"
device = "/dev/video0"
width = 640
height = 480
fps = 15
pixel_format = "yuyv"
timeout_ms = 500

[depth]
backend = "sr2"
fps = 10
timeout_ms = 500

[pairing]
# Wider than the default 1.5 depth periods: under TCG the SR-2's frames come
# irregularly, and one dropped frame must not unpair colour frames.
max_skew_ms = 350

[mapping]
# Fitted by tests/hil/run.sh with depthkey-calibrate --sim (640x480 colour).
calibration_file = "$VM_RESULTS/calibration.toml"

[board]
# The second vivid instance as the board computer's capture stick, at a
# size TCG keeps up with; the board calibration fitted by tests/hil/run.sh
# (depthkey-calibrate --board --sim --board-size 640x360).
backend = "v4l2"
device = "/dev/video1"
width = 640
height = 360
fps = 5
pixel_format = "yuyv"
timeout_ms = 1000
homography_file = "$VM_RESULTS/board.toml"

[leds]
backend = "gpiod"
chip = "$led_chip"
power_line = $LED_POWER
depth_line = $LED_DEPTH
colour_line = $LED_COLOUR
calibration_line = $LED_CALIBRATION
reader_line = $LED_READER
error_line = $LED_ERROR
board_line = $LED_BOARD
TOML

if ! out=$("$HIL_BIN/depthkeyd" --check-config "$DK_CONFIG" 2>&1); then
	if echo "$out" | grep -q 'backend'; then
		hil_skip daemon "this depthkeyd has no v4l2/sr2/gpiod backends: $(echo "$out" | head -n1)"
	else
		hil_fail daemon-config "$out"
	fi
	return 0
fi

shm_watch() { "$HIL_BIN/depthkey-hil-shm-watch" "$@"; }
lost_count() { grep -c "$1 lost" "$DK_LOG"; }
lost_more_than() { [ "$(lost_count "$1")" -gt "$2" ]; }
daemon_alive() { kill -0 "$DK_PID" 2>/dev/null; }

# check_flags NAME MASK=VALUE COUNT [watch options]: COUNT consecutive new
# frames with those flags.
check_flags() {
	local name=$1 until=$2 count=$3
	shift 3
	hil_check "$name" shm_watch --until "$until" --count "$count" --timeout 30 "$@"
}

# check_led NAME LINE PATTERN: the line shows PATTERN (on/off/blinking),
# sampled for 1.5 s (the slowest blink is 1 Hz); retried for up to 15 s: the
# LEDs follow the device state, which lags the frame flags (ten bad SR-2
# frames make it lost: seconds in the sanitizer build under TCG).
check_led() {
	local name=$1 line=$2 want=$3 got deadline
	deadline=$(($(hil_now_cs) + 1500))
	while :; do
		got=$(gpio_pattern "$line" 150)
		[ "$got" = "$want" ] && { hil_pass "$name" "line $line $got"; return; }
		[ "$(hil_now_cs)" -lt "$deadline" ] || break
	done
	hil_fail "$name" "line $line is $got, expected $want"
}

# recovery_watch_start: starts a watcher for the first whole frame before a
# device is brought back, so that its own start-up (slow under TCG) does not
# count; recovery_check NAME SINCE then takes the time from SINCE (the uptime
# at which the device returned) to that frame, logs it for the summary and
# holds it against the 2 s limit.
recovery_watch_start() {
	# 9<&-: the watcher must not hold the webcam that the suite keeps away.
	shm_watch --until "$ONLINE=$ONLINE" --timeout 60 >/run/hil-recovery-watch 9<&- &
	RECOVERY_WATCH=$!
}
recovery_check() {
	local name=$1 since=$2 out ms seconds
	wait "$RECOVERY_WATCH"
	out=$(cat /run/hil-recovery-watch)
	if [[ $out =~ \ at\ ([0-9.]+) ]] && [ -n "$since" ]; then
		ms=$(awk -v a="${BASH_REMATCH[1]}" -v b="$since" 'BEGIN { printf "%d", (a - b) * 1000 }')
		seconds=$(awk -v ms="$ms" 'BEGIN { printf "%.3f", ms / 1000 }')
		echo "$name $seconds" >>"$RECOVERY_LOG"
		if [ "$HIL_SANITIZER" = 1 ]; then
			hil_pass "$name-recovery" "whole frames again $seconds s after the device returned"
			hil_skip "$name-recovery-time" "not judged in the sanitizer build ($seconds s)"
		elif [ "$ms" -le "$RECOVERY_LIMIT_MS" ]; then
			hil_pass "$name-recovery" "whole frames again $seconds s after the device returned"
		else
			hil_fail "$name-recovery" "whole frames again only $seconds s after the device returned (limit 2 s)"
		fi
	else
		hil_fail "$name-recovery" "${out:-no result} (device returned at ${since:-?})"
	fi
}

# fault NAME INJECT OFFLINE_FLAG LED RESTORE: injects a fault (a command),
# expects frames with OFFLINE_FLAG cleared and the device's LED blinking
# while the daemon runs on, then restores and times the recovery: from the
# restoring command, or for a replug from the moment the host has configured
# the device again (sr2_replug).
fault() {
	local name=$1 inject=$2 flag=$3 led=$4 restore=$5 since
	if ! $inject; then
		hil_fail "$name-inject" "could not inject: $inject"
		return
	fi
	check_flags "$name-offline-frames" "$flag=0" 3
	check_led "$name-led-blinks" "$led" blinking
	hil_check "$name-daemon-runs" daemon_alive
	recovery_watch_start
	since=$(hil_uptime)
	SR2_RETURNED_AT=""
	$restore || hil_fail "$name-restore" "could not restore: $restore"
	recovery_check "$name" "${SR2_RETURNED_AT:-$since}"
	check_led "$name-led-on-again" "$led" on
}

# --- start --------------------------------------------------------------------
{ "$HIL_BIN/depthkeyd" --config "$DK_CONFIG"; echo "hil: depthkeyd exit status $?"; } 2>&1 |
	hil_timestamp >"$DK_LOG" &
hil_wait 20 pidof depthkeyd && DK_PID=$(pidof depthkeyd)
check_flags daemon-frames-from-both-cameras "$ONLINE=$ONLINE" 10 --timeout 60
# The simulated figure covers about a fifth of the view: keyed from the SR-2's
# depth, the lecturer layer is neither empty nor everything.
check_flags daemon-lecturer-keyed-by-sr2-depth "$ONLINE=$ONLINE" 3 --name /depthkey.lecturer \
	--alpha-between 0.05 0.6
hil_check daemon-sr2-output-mode hil_wait 10 grep -q 'register 0x02 = 0xc0' "$SR2_LOG"
hil_check daemon-sr2-integration-time hil_wait 10 grep -q 'register 0x09 = 0x28' "$SR2_LOG"
check_led led-power-heartbeat $LED_POWER blinking
check_led led-depth-on $LED_DEPTH on
check_led led-colour-on $LED_COLOUR on
check_led led-calibration-loaded $LED_CALIBRATION off
check_led led-error-off $LED_ERROR off
check_led led-board-on $LED_BOARD on
# Board geometry: the board-geometry lecturer layer is published beside the
# camera's, and the status says so.
check_flags daemon-board-geometry-layer "$ONLINE=$ONLINE" 3 --name /depthkey.lecturer.board
hil_check daemon-status-board-geometry hil_wait 15 grep -q 'board v4l2-board streaming, board geometry 640x360' "$DK_LOG"
# Reader presence: the reader LED is off with no reader, on while
# depthkey-shmcat reads (its heartbeats), and off again once it is killed.
check_led led-reader-off-without-reader $LED_READER off
"$HIL_BIN/depthkey-shmcat" --timeout 60 >/dev/null 2>&1 9<&- &
SHMCAT_PID=$!
check_led led-reader-on-while-shmcat-reads $LED_READER on
kill -KILL "$SHMCAT_PID"
wait "$SHMCAT_PID" 2>/dev/null
check_led led-reader-off-after-reader-killed $LED_READER off

# --- virtual webcam ---------------------------------------------------------------
# ffmpeg reads the v4l2loopback device as a camera; its frame must be the
# shared-memory composite: both scaled to 64x36 (the composite is the board
# geometry's 640x360), mean absolute difference per channel under 12 levels
# (they are taken a few frames apart, and the lecturer moves; a wrong
# conversion, e.g. U and V swapped or luma off by its range, gives 20-60 on
# this picture). The same measure against the composite mirrored is printed
# as what an unrelated picture scores. The webcam is switched on by a reload
# (SIGHUP) for this section and off again after it, so that the fault
# sections' recovery times are measured as before, without the conversion
# (slow under TCG) on the loop.
webcam_mad() { # FILE FILE: mean absolute difference of two raw RGB24 files
	# (temporary files: the VM has no /dev/fd for process substitution)
	od -An -v -tu1 -w1 "$1" >/run/webcam-mad.a && od -An -v -tu1 -w1 "$2" >/run/webcam-mad.b &&
		paste /run/webcam-mad.a /run/webcam-mad.b |
		awk '{ d = $1 - $2; s += d < 0 ? -d : d; n++ } END { if (n != 64 * 36 * 3) exit 1; printf "%.2f", s / n }'
}
if hil_section webcam-output; then
	if [ -n "${WEBCAM_MISSING:-}" ]; then
		hil_skip webcam-output "$WEBCAM_MISSING"
	else
		cp "$DK_CONFIG" "$DK_CONFIG.before-webcam"
		printf '\n[output]\nv4l2_device = "/dev/video10"\n' >>"$DK_CONFIG"
		kill -HUP "$DK_PID"
		hil_check webcam-status-writing hil_wait 20 grep -q 'webcam /dev/video10 writing' "$DK_LOG"
		scale="scale=64:36:flags=area"
		if ! out=$(timeout 60 ffmpeg -nostdin -loglevel error -f v4l2 -i /dev/video10 -frames:v 3 \
			-vf "$scale" -f rawvideo -pix_fmt rgb24 -y /run/webcam3.rgb 2>&1 9<&-) ||
			! tail -c $((64 * 36 * 3)) /run/webcam3.rgb >/run/webcam.rgb; then
			hil_fail webcam-ffmpeg-reads "$(echo "$out" | tail -n2 | tr '\n' ' ')"
		elif ! out=$("$HIL_BIN/depthkey-shmcat" --frames 1 --timeout 10 9<&- 2>&1 >/run/composite.y4m) ||
			! ffmpeg -nostdin -loglevel error -y -i /run/composite.y4m -vf "$scale" -f rawvideo -pix_fmt rgb24 \
				/run/composite.rgb ||
			! ffmpeg -nostdin -loglevel error -y -i /run/composite.y4m -vf "hflip,$scale" -f rawvideo \
				-pix_fmt rgb24 /run/composite-mirrored.rgb; then
			hil_fail webcam-ffmpeg-reads "the shared-memory composite could not be read: $out"
		else
			hil_pass webcam-ffmpeg-reads "ffmpeg -f v4l2 -i /dev/video10: $(stat -c %s /run/webcam.rgb) bytes at 64x36"
			mad=$(webcam_mad /run/webcam.rgb /run/composite.rgb)
			unrelated=$(webcam_mad /run/webcam.rgb /run/composite-mirrored.rgb)
			if [[ ! $mad =~ ^[0-9]+\.[0-9]+$ ]]; then
				hil_fail webcam-matches-composite "no difference measured (${mad:-empty}): $(stat -c %s /run/webcam.rgb /run/composite.rgb | tr '\n' ' ')"
			elif awk -v m="$mad" 'BEGIN { exit !(m + 0 < 12) }'; then
				hil_pass webcam-matches-composite "mean abs difference $mad levels (< 12; mirrored composite $unrelated)"
			else
				hil_fail webcam-matches-composite "mean abs difference $mad levels, limit 12 (mirrored composite $unrelated)"
			fi
		fi
		mv "$DK_CONFIG.before-webcam" "$DK_CONFIG"
		kill -HUP "$DK_PID"
		# The status line, printed every few seconds, no longer names it.
		hil_check webcam-off-after-reload hil_wait 30 sh -c \
			"grep 'fps; readers' '$DK_LOG' | tail -n 1 | grep -v -q 'webcam /dev/video10'"
	fi
fi

# --- SR-2 faults ----------------------------------------------------------------
sr2() { sr2_cmd "$@"; }
if hil_section sr2; then
	fault sr2-unplug "sr2 unplug" $DEPTH_OK $LED_DEPTH sr2_replug
	fault sr2-stall "sr2 stall" $DEPTH_OK $LED_DEPTH "sr2 resume"
	fault sr2-corrupt-frames "sr2 corrupt 100000" $DEPTH_OK $LED_DEPTH "sr2 corrupt 0"
	fault sr2-flat-frames "sr2 flat 100000" $DEPTH_OK $LED_DEPTH "sr2 flat 0"
	fault sr2-short-frames "sr2 short 100000" $DEPTH_OK $LED_DEPTH "sr2 short 0"
	fault sr2-request-stalls "sr2 halt 100000" $DEPTH_OK $LED_DEPTH "sr2 halt 0"
	# One bad frame is dropped and counted, not a lost camera. (Depth may still
	# miss the pairing window for a frame or two under TCG's uneven timing, so
	# this is judged by the daemon's own account, not the frame flags.)
	sr2_dropped() { sed -n 's/.* depth sr2 [a-z]* [0-9.]* fps \([0-9]*\) dropped.*/\1/p' "$DK_LOG" | tail -n1; }
	dropped_more_than() { [ "$(sr2_dropped)" -gt "$1" ]; }
	lost=$(lost_count sr2) dropped=$(sr2_dropped)
	sr2_cmd corrupt 1
	if hil_wait 15 dropped_more_than "${dropped:-0}"; then
		if [ "$(lost_count sr2)" -eq "$lost" ]; then
			hil_pass sr2-one-corrupt-frame-dropped "dropped count $dropped -> $(sr2_dropped), camera not lost"
		else
			hil_fail sr2-one-corrupt-frame-dropped "one corrupt frame made the camera lost"
		fi
	else
		hil_fail sr2-one-corrupt-frame-dropped "the dropped count stayed ${dropped:-?}"
	fi
	check_led sr2-one-corrupt-frame-led-on $LED_DEPTH on
fi

# --- webcam (vivid) faults ---------------------------------------------------
# vivid's "disconnect" unregisters the device until its last user closes it.
# The suite holds it open (fd 9) to keep it away, like an unplugged webcam,
# and lets it return by closing that fd. Injected errors hit the next such
# call (stream on, buffer allocation) when the daemon re-opens it.
vivid() { v4l2-ctl -d /dev/video0 -c "$1=1"; }
webcam_unplug() {
	local name=$1 since
	shift
	exec 9</dev/video0
	for control in "$@" disconnect; do
		vivid "$control" || hil_fail "$name-inject" "v4l2-ctl -c $control=1 failed"
	done
	check_flags "$name-offline-frames" "$COLOUR_OK=0" 3
	check_led "$name-led-blinks" $LED_COLOUR blinking
	hil_check "$name-daemon-runs" daemon_alive
	recovery_watch_start
	since=$(hil_uptime)
	exec 9<&-
	recovery_check "$name" "$since"
	check_led "$name-led-on-again" $LED_COLOUR on
}
# A failing call on a present device: the daemon re-opens it at once, often
# before three frame periods pass, i.e. before NO SIGNAL frames are due. The
# recovery is timed from the injection to the daemon's "streaming again".
again_count() { grep -c "$1 streaming again" "$DK_LOG"; }
again_more_than() { [ "$(again_count "$1")" -gt "$2" ]; }
webcam_error() {
	local name=$1 control=$2 lost again since back ms seconds
	lost=$(lost_count v4l2-colour) again=$(again_count v4l2-colour)
	since=$(hil_uptime)
	vivid "$control" || hil_fail "$name-inject" "v4l2-ctl -c $control=1 failed"
	hil_check "$name-noticed" hil_wait 10 lost_more_than v4l2-colour "$lost"
	hil_check "$name-daemon-runs" daemon_alive
	if hil_wait 10 again_more_than v4l2-colour "$again"; then
		back=$(grep 'v4l2-colour streaming again' "$DK_LOG" | tail -n1 | sed 's/^\[\([0-9.]*\)\].*/\1/')
		ms=$(awk -v a="$back" -v b="$since" 'BEGIN { printf "%d", (a - b) * 1000 }')
		seconds=$(awk -v ms="$ms" 'BEGIN { printf "%.3f", ms / 1000 }')
		echo "$name $seconds" >>"$RECOVERY_LOG"
		[ "$HIL_SANITIZER" = 1 ] && hil_skip "$name-recovery-time" "not judged in the sanitizer build ($seconds s)"
		[ "$HIL_SANITIZER" = 1 ] || [ "$ms" -le "$RECOVERY_LIMIT_MS" ] &&
			hil_pass "$name-recovery" "streaming again $seconds s after the error" ||
			hil_fail "$name-recovery" "streaming again only $seconds s after the error (limit 2 s)"
	else
		hil_fail "$name-recovery" "not streaming again 10 s after the error"
	fi
	check_flags "$name-whole-frames" "$ONLINE=$ONLINE" 3
}
if hil_section webcam; then
	webcam_unplug webcam-unplug
	webcam_unplug webcam-unplug-streamon-fails inject_vidioc_streamon_error
	webcam_unplug webcam-unplug-reqbufs-fails inject_vidioc_reqbufs_error
	webcam_error webcam-qbuf-error inject_vidioc_qbuf_error
	webcam_error webcam-fatal-streaming-error inject_fatal_streaming_error
	vivid inject_v4l2_buf_flag_error
	if out=$(shm_watch --until "$COLOUR_OK=0" --timeout 3); then
		hil_fail webcam-error-buffer-dropped "colour went offline for one error buffer: $out"
	else
		hil_pass webcam-error-buffer-dropped "colour stayed online for 3 s"
	fi
fi

# --- the board's capture stick (second vivid) unplugged and back -------------------
# The output goes on, online, with the last good board picture; the board LED
# blinks fast and the status says so; back within 2 s of its return.
board_vivid() { v4l2-ctl -d /dev/video1 -c "$1=1"; }
board_status_lost() { grep -q 'board v4l2-board lost (last good picture kept)' "$DK_LOG"; }
if hil_section board; then
	lost=$(lost_count v4l2-board) again=$(again_count v4l2-board)
	exec 7</dev/video1 # fd 7: 8 is hil_sleep's, 9 the webcam's
	board_vivid disconnect || hil_fail board-unplug-inject "v4l2-ctl -c disconnect=1 failed"
	hil_check board-unplug-noticed hil_wait 15 lost_more_than v4l2-board "$lost"
	check_flags board-unplug-output-stays-online "$ONLINE=$ONLINE" 3
	check_led board-unplug-led-blinks $LED_BOARD blinking
	hil_check board-unplug-status-says-lost hil_wait 15 board_status_lost
	hil_check board-unplug-daemon-runs daemon_alive
	since=$(hil_uptime)
	exec 7<&-
	if hil_wait 15 again_more_than v4l2-board "$again"; then
		back=$(grep 'v4l2-board streaming again' "$DK_LOG" | tail -n1 | sed 's/^\[\([0-9.]*\)\].*/\1/')
		ms=$(awk -v a="$back" -v b="$since" 'BEGIN { printf "%d", (a - b) * 1000 }')
		seconds=$(awk -v ms="$ms" 'BEGIN { printf "%.3f", ms / 1000 }')
		echo "board-unplug $seconds" >>"$RECOVERY_LOG"
		[ "$HIL_SANITIZER" = 1 ] || [ "$ms" -le "$RECOVERY_LIMIT_MS" ] &&
			hil_pass board-unplug-recovery "board streaming again $seconds s after its return" ||
			hil_fail board-unplug-recovery "board streaming again only $seconds s after its return (limit 2 s)"
	else
		hil_fail board-unplug-recovery "the board was not streaming again 15 s after its return"
	fi
	check_led board-unplug-led-on-again $LED_BOARD on
	check_flags board-geometry-layer-again "$ONLINE=$ONLINE" 3 --name /depthkey.lecturer.board
fi

# --- leaks over 50 unplug/replug cycles ----------------------------------------
fd_count() { local n=0 f; for f in /proc/"$DK_PID"/fd/*; do n=$((n + 1)); done; echo "$n"; }
rss_kb() { sed -n 's/^VmRSS:[[:space:]]*\([0-9]*\) kB/\1/p' /proc/"$DK_PID"/status; }
replug_cycle() {
	local since out
	sr2_cmd unplug || { echo "unplug command failed"; return 1; }
	out=$(shm_watch --until "$DEPTH_OK=0" --timeout 20) || { echo "no offline frame: $out"; return 1; }
	recovery_watch_start
	sr2_replug || { echo "replug failed"; return 1; }
	wait "$RECOVERY_WATCH" || { cat /run/hil-recovery-watch; return 1; }
	[[ $(cat /run/hil-recovery-watch) =~ \ at\ ([0-9.]+) ]] &&
		awk -v a="${BASH_REMATCH[1]}" -v b="$SR2_RETURNED_AT" 'BEGIN { printf "cycle %.3f\n", a - b }' >>"$RECOVERY_LOG"
	return 0
}
if hil_section leak; then
	# Five cycles first: what a re-open allocates once (libusb's and glibc's
	# pools, per-thread arenas) is not a leak. Then 50 measured cycles.
	for i in 1 2 3 4 5; do replug_cycle >/dev/null; done
	shm_watch --until "$ONLINE=$ONLINE" --count 5 --timeout 30 >/dev/null
	fds_before=$(fd_count) rss_before=$(rss_kb)
	cycles=0 why=""
	while [ "$cycles" -lt 50 ] && why=$(replug_cycle); do
		cycles=$((cycles + 1))
	done
	shm_watch --until "$ONLINE=$ONLINE" --count 5 --timeout 30 >/dev/null
	fds_after=$(fd_count) rss_after=$(rss_kb)
	if [ "$cycles" -eq 50 ]; then
		hil_pass sr2-50-replug-cycles "50 cycles, each back online"
		[ "$fds_after" -eq "$fds_before" ] && hil_pass no-fd-leak "$fds_before fds before, $fds_after after" ||
			hil_fail no-fd-leak "$fds_before fds before, $fds_after after 50 cycles"
		# Freed memory may stay in the allocator's pools: allow 1 MB, far
		# less than 50 frames' worth. AddressSanitizer holds freed memory in
		# quarantine, so the sanitizer build leaves this to LeakSanitizer.
		if [ "$HIL_SANITIZER" = 1 ]; then
			hil_skip no-memory-leak "VmRSS $rss_before -> $rss_after kB not judged under ASan (quarantine)"
		else
			[ $((rss_after - rss_before)) -le 1024 ] &&
				hil_pass no-memory-leak "VmRSS $rss_before kB before, $rss_after kB after" ||
				hil_fail no-memory-leak "VmRSS grew from $rss_before kB to $rss_after kB over 50 cycles"
		fi
	else
		hil_fail sr2-50-replug-cycles "cycle $((cycles + 1)): $why"
	fi
fi

# --- stop -------------------------------------------------------------------------
kill -TERM "$DK_PID"
hil_check daemon-stops hil_wait 20 sh -c "! kill -0 $DK_PID"
hil_check daemon-clean-stop hil_wait 10 grep -q 'hil: depthkeyd exit status 0' "$DK_LOG"
dark=1
for line in $LED_POWER $LED_DEPTH $LED_COLOUR $LED_CALIBRATION $LED_READER $LED_ERROR $LED_BOARD; do
	[ "$(gpio_value "$line")" = 0 ] || dark=0
done
[ "$dark" -eq 1 ] && hil_pass leds-dark-after-stop "all seven lines low" || hil_fail leds-dark-after-stop "a line is still high"
