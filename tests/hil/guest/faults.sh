# The real depthkeyd against the virtual devices, and the faults injected
# into them (sourced, after lib.sh): the daemon's config and start, the
# shared-memory watcher, each fault's injection and its undoing, recovery
# timing and the daemon's fds and VmRSS. Shared by daemon.sh (the HIL suite:
# each fault once, with its LEDs) and campaign.sh (`make hil-campaign`: many
# faults in a seeded random order).

DK_CONFIG=/run/hil-depthkey.toml
DK_LOG=$HIL_LOGS/depthkeyd.log
RECOVERY_LOG=$VM_RESULTS/recovery
RECOVERY_LIMIT_MS=2000
# Freed memory may stay in the allocator's pools: VmRSS may grow this much
# over many faults before it counts as a leak (far less than 50 frames).
LEAK_RSS_LIMIT_KB=1024
# HIL_SANITIZER=1: the binaries are the sanitizer build, several times slower
# under TCG and holding freed memory in ASan's quarantine: recovery times and
# VmRSS are then reported as skipped; recovery itself is still asserted.
HIL_SANITIZER=${HIL_SANITIZER:-0}
# Shared-memory flags (hal/depthkey_shm.h).
ONLINE=0x7 COLOUR_OK=0x2 DEPTH_OK=0x4
# LED lines on the simulated chip (the legend in docs/devices.md).
LED_POWER=0 LED_DEPTH=1 LED_COLOUR=2 LED_CALIBRATION=3 LED_READER=4 LED_ERROR=5 LED_BOARD=6
LED_LINES="$LED_POWER $LED_DEPTH $LED_COLOUR $LED_CALIBRATION $LED_READER $LED_ERROR $LED_BOARD"

cat >"$DK_CONFIG" <<TOML
[colour]
backend = "v4l2"
device = "/dev/video0"
# vivid's smallest webcam size. This suite tests how the daemon handles its
# devices, not what it keys (tests/process/accuracy_gate_test.cpp does), and
# the 2 s recoveries are the devices' own: at 640x480 a keyed frame took
# 150-310 ms of the VM's CPU under TCG, each USB or V4L2 step of a returning
# device waited for one, and CI measured recoveries 2.06-2.40 s (stops 21,
# 22) though the same steps take some 100 ms natively. 320x180 has 5.3
# times fewer pixels to key.
width = 320
height = 180
# 10, not 15: under TCG the daemon keys some 200 ms a frame and sheds the rest
# (daemon/keying_worker.hpp) either way, and the frames vivid renders and the
# daemon converts cost the VM's CPU that the SR-2 emulator and the board's
# vivid need for their frames (the board's recovery measured 2.1-2.3 s).
fps = 10
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

[decision]
# The band's minimum cut costs some 25 ms a frame at 640x480 natively and
# several hundred under TCG, a frame period or more: colour frames
# would leave unkeyed, without depth. This suite tests the devices, not the
# segmentation (tests/process/accuracy_gate_test.cpp does): smoothing here,
# and no edge unmixing (a few ms natively, tens under TCG).
cut_smoothness = 0
edge_unmixing = 0

[mapping]
# Fitted by tests/hil/run.sh with depthkey-calibrate --sim (320x180 colour).
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

# daemon_config_usable: true when this depthkeyd accepts the config; a
# depthkeyd built without the device backends is a skip, anything else a
# failure (both recorded).
daemon_config_usable() {
	local out
	out=$("$HIL_BIN/depthkeyd" --check-config "$DK_CONFIG" 2>&1) && return 0
	if echo "$out" | grep -q 'backend'; then
		hil_skip daemon "this depthkeyd has no v4l2/sr2/gpiod backends: $(echo "$out" | head -n1)"
	else
		hil_fail daemon-config "$out"
	fi
	return 1
}

# daemon_start: starts depthkeyd on the config, its output timestamped into
# DK_LOG (appended: a restart after a crash keeps the crash's lines), and
# sets DK_PID.
daemon_start() {
	{ "$HIL_BIN/depthkeyd" --config "$DK_CONFIG"; echo "hil: depthkeyd exit status $?"; } 2>&1 |
		hil_timestamp >>"$DK_LOG" &
	hil_wait 20 pidof depthkeyd && DK_PID=$(pidof depthkeyd)
}

shm_watch() { "$HIL_BIN/depthkey-hil-shm-watch" "$@"; }
lost_count() { grep -c "$1 lost" "$DK_LOG"; }
lost_more_than() { [ "$(lost_count "$1")" -gt "$2" ]; }
again_count() { grep -c "$1 streaming again" "$DK_LOG"; }
reload_count() { grep -c "configuration reloaded" "$DK_LOG"; }
reloaded_more_than() { [ "$(reload_count)" -gt "$1" ]; }
again_more_than() { [ "$(again_count "$1")" -gt "$2" ]; }
# again_at DEVICE: the uptime of the daemon's last "DEVICE streaming again".
again_at() { grep "$1 streaming again" "$DK_LOG" | tail -n1 | sed 's/^\[\([0-9.]*\)\].*/\1/'; }
daemon_alive() { kill -0 "$DK_PID" 2>/dev/null; }
# fd_split: "OTHER VIDEO": the daemon's fds other than V4L2 nodes, and the
# most fds open on any one /dev/video node. A camera or the board's stick
# that is re-opening has its node closed for a moment (under TCG the board's
# vivid misses its 1 s timeout every few seconds), so a plain count differs
# by one with the moment it is taken; a leaked node fd shows as 2 on a node.
fd_split() {
	local f
	for f in /proc/"$DK_PID"/fd/*; do readlink "$f"; done 2>/dev/null |
		awk '/^\/dev\/video/ { v[$0]++; next } { n++ } END { m = 0; for (k in v) if (v[k] > m) m = v[k]; print n + 0, m }'
}
# fd_names: what the daemon's fds are (sorted, for comm), to say which are new.
fd_names() { local f; for f in /proc/"$DK_PID"/fd/*; do readlink "$f"; done 2>/dev/null | sort; }
rss_kb() { sed -n 's/^VmRSS:[[:space:]]*\([0-9]*\) kB/\1/p' /proc/"$DK_PID"/status; }
# rss_settled_kb: the least VmRSS of five samples 0.2 s apart. Large blocks
# live for a moment (a NO SIGNAL picture, a frame in flight) are mmapped and
# returned as they are freed, so one sample swings by a megabyte or two
# either way; a leak raises the least of them too.
rss_settled_kb() {
	local least="" kb i
	for i in 1 2 3 4 5; do
		kb=$(rss_kb)
		{ [ -z "$least" ] || [ "$kb" -lt "$least" ]; } && least=$kb
		sleep 0.2
	done
	echo "$least"
}

# elapsed_ms SINCE UNTIL: milliseconds between two uptimes; ms_seconds MS:
# those as seconds with three decimals.
elapsed_ms() { awk -v a="$2" -v b="$1" 'BEGIN { printf "%d", (a - b) * 1000 }'; }
ms_seconds() { awk -v ms="$1" 'BEGIN { printf "%.3f", ms / 1000 }'; }

# led_shows LINE PATTERN: the line shows PATTERN (on/off/blinking), sampled
# for 1.5 s (the slowest blink is 1 Hz); retried for up to 15 s: the LEDs
# follow the device state, which lags the frame flags (ten bad SR-2 frames
# make it lost: seconds in the sanitizer build under TCG), and a starved VM
# may sample a blink too seldom. LED_SEEN is the last pattern seen.
led_shows() {
	local deadline
	deadline=$(($(hil_now_cs) + 1500))
	while :; do
		LED_SEEN=$(gpio_pattern "$1" 150)
		[ "$LED_SEEN" = "$2" ] && return 0
		[ "$(hil_now_cs)" -lt "$deadline" ] || return 1
	done
}

# check_flags NAME MASK=VALUE COUNT [watch options]: COUNT consecutive new
# frames with those flags.
check_flags() {
	local name=$1 until=$2 count=$3
	shift 3
	hil_check "$name" shm_watch --until "$until" --count "$count" --timeout 30 "$@"
}

# recovery_watch_start: starts a watcher for the first whole frame before a
# device is brought back, so that its own start-up (slow under TCG) does not
# count; recovery_measure SINCE then waits for it and sets RECOVERY_MS to the
# milliseconds from SINCE (the uptime at which the device returned) to that
# frame, or fails with RECOVERY_WHY. (Not in a command substitution: the
# watcher is this shell's child.)
recovery_watch_start() {
	# 9<&-: the watcher must not hold the webcam that the suite keeps away.
	shm_watch --until "$ONLINE=$ONLINE" --timeout 60 >/run/hil-recovery-watch 9<&- &
	RECOVERY_WATCH=$!
}
recovery_measure() {
	local since=$1 out
	wait "$RECOVERY_WATCH"
	out=$(cat /run/hil-recovery-watch)
	RECOVERY_MS="" RECOVERY_WHY=""
	if [[ $out =~ \ at\ ([0-9.]+) ]] && [ -n "$since" ]; then
		RECOVERY_MS=$(elapsed_ms "$since" "${BASH_REMATCH[1]}")
	else
		RECOVERY_WHY="${out:-no result} (device returned at ${since:-?})"
		return 1
	fi
}

# --- the faults: each injected and undone by name ------------------------------
# SR-2: the emulator's commands (tools/sr2_emulator). A replug sets
# SR2_RETURNED_AT (the device is back once the host has configured it).
SR2_FAULTS="unplug stall corrupt flat short halt"
sr2_inject() {
	case $1 in
	unplug | stall) sr2_cmd "$1" ;;
	corrupt | flat | short | halt) sr2_cmd "$1" 100000 ;;
	*) echo "no SR-2 fault $1" >&2; return 1 ;;
	esac
}
sr2_restore() {
	case $1 in
	unplug) sr2_replug ;;
	stall) sr2_cmd resume ;;
	corrupt | flat | short | halt) sr2_cmd "$1" 0 ;;
	*) echo "no SR-2 fault $1" >&2; return 1 ;;
	esac
}

# The webcam (vivid). Its "disconnect" unregisters the device until its last
# user closes it: webcam_away NAME [CONTROL...] holds it open (fd 9) to keep
# it away, like an unplugged webcam, after setting vivid's error controls
# given (they hit the next such call, e.g. stream on, when the daemon
# re-opens it); webcam_back lets it return by closing that fd. webcam_error
# NAME CONTROL injects an error into the streaming device (the daemon re-opens
# it at once). A control that cannot be set fails NAME-inject.
vivid() { v4l2-ctl -d /dev/video0 -c "$1=1"; }
webcam_away() {
	local name=$1 control
	shift
	exec 9</dev/video0
	for control in "$@" disconnect; do
		vivid "$control" || hil_fail "$name-inject" "v4l2-ctl -c $control=1 failed"
	done
}
webcam_back() { exec 9<&-; }
webcam_error() { vivid "$2" || hil_fail "$1-inject" "v4l2-ctl -c $2=1 failed"; }

# The LEDs' GPIO chip (gpio-sim) removed and back: the daemon's lines fail
# (released and logged once, the daemon goes on: docs/devices.md). A new chip
# may have a new name: led_chip follows it.
gpio_chip_remove() { echo 0 >"$GPIO_SIM/live"; }
gpio_chip_return() {
	echo 1 >"$GPIO_SIM/live" && led_chip=$(cat "$GPIO_SIM/bank0/chip_name") && hil_wait 10 test -c "/dev/$led_chip"
}

# The GPIO lines the daemon holds (its LEDs), from its fds.
lines_held() { find /proc/"$DK_PID"/fd -lname 'anon_inode:gpio-line*' 2>/dev/null | wc -l; }
lines_are() { [ "$(lines_held)" -eq "$1" ]; }
lines_below() { [ "$(lines_held)" -lt "$1" ]; }
LED_COUNT=$(set -- $LED_LINES; echo $#)

# daemon_stop_checks: SIGTERM; the daemon must stop cleanly (status 0) and
# leave every LED dark.
daemon_stop_checks() {
	local dark=1 line
	kill -TERM "$DK_PID"
	hil_check daemon-stops hil_wait 20 sh -c "! kill -0 $DK_PID"
	hil_check daemon-clean-stop hil_wait 10 grep -q 'hil: depthkeyd exit status 0' "$DK_LOG"
	for line in $LED_LINES; do
		[ "$(gpio_value "$line")" = 0 ] || dark=0
	done
	[ "$dark" -eq 1 ] && hil_pass leds-dark-after-stop "all seven lines low" || hil_fail leds-dark-after-stop "a line is still high"
}
