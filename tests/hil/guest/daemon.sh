# The real depthkeyd against the virtual devices (sourced by main.sh): the
# V4L2 backend on vivid, the SR-2 backend on the emulated camera, the gpiod
# LEDs on gpio-sim. Asserts frames flow, then injects each fault and checks
# that the daemon keeps running and publishing frames marked offline, shows
# it on the LEDs, and recovers within 2 s of the device's return; finally 50
# unplug/replug cycles must not leak file descriptors or memory.

DK_CONFIG=/run/hil-depthkey.toml
DK_LOG=$HIL_LOGS/depthkeyd.log
RECOVERY_LOG=$VM_RESULTS/recovery
RECOVERY_LIMIT_MS=2000
# Shared-memory flags (hal/depthkey_shm.h).
ONLINE=0x7 COLOUR_OK=0x2 DEPTH_OK=0x4
# LED lines on the simulated chip (the README's legend).
LED_POWER=0 LED_DEPTH=1 LED_COLOUR=2 LED_CALIBRATION=3 LED_READER=4 LED_ERROR=5

cat >"$DK_CONFIG" <<TOML
[colour]
backend = "v4l2"
device = "/dev/video0"
width = 320
height = 180
fps = 15
pixel_format = "yuyv"
timeout_ms = 500

[depth]
backend = "sr2"
fps = 10
timeout_ms = 500

[leds]
backend = "gpiod"
chip = "$led_chip"
power_line = $LED_POWER
depth_line = $LED_DEPTH
colour_line = $LED_COLOUR
calibration_line = $LED_CALIBRATION
reader_line = $LED_READER
error_line = $LED_ERROR
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
daemon_alive() { kill -0 "$DK_PID" 2>/dev/null; }

# check_flags NAME MASK=VALUE COUNT [watch options]: COUNT consecutive new
# frames with those flags.
check_flags() {
	local name=$1 until=$2 count=$3
	shift 3
	hil_check "$name" shm_watch --until "$until" --count "$count" --timeout 30 "$@"
}

# check_led NAME LINE PATTERN: the line shows PATTERN (on/off/blinking),
# sampled for 1.5 s (the slowest blink is 1 Hz); retried for up to 6 s since
# the LEDs follow the state on the daemon's next tick.
check_led() {
	local name=$1 line=$2 want=$3 got deadline
	deadline=$(($(hil_now_cs) + 600))
	while :; do
		got=$(gpio_pattern "$line" 1.5)
		[ "$got" = "$want" ] && { hil_pass "$name" "line $line $got"; return; }
		[ "$(hil_now_cs)" -lt "$deadline" ] || break
	done
	hil_fail "$name" "line $line is $got, expected $want"
}

# check_recovery NAME SINCE: all flags back within the limit of SINCE (the
# uptime when the device returned). Logs the time for the summary.
check_recovery() {
	local name=$1 since=$2 out seconds ms
	out=$(shm_watch --until "$ONLINE=$ONLINE" --since "$since" --timeout 30)
	if [[ $out =~ after\ ([0-9]+)\.([0-9]{3})\ s ]]; then
		seconds="${BASH_REMATCH[1]}.${BASH_REMATCH[2]}"
		ms=$((10#${BASH_REMATCH[1]} * 1000 + 10#${BASH_REMATCH[2]}))
		echo "$name $seconds" >>"$RECOVERY_LOG"
		if [ "$ms" -le "$RECOVERY_LIMIT_MS" ]; then
			hil_pass "$name-recovery" "online again $seconds s after the device returned"
		else
			hil_fail "$name-recovery" "online again only $seconds s after the device returned (limit 2 s)"
		fi
	else
		hil_fail "$name-recovery" "$out"
	fi
}

# fault NAME INJECT OFFLINE_FLAG LED RESTORE: injects a fault (a command),
# expects frames with OFFLINE_FLAG cleared and the device's LED blinking
# while the daemon runs on, then restores and times the recovery.
fault() {
	local name=$1 inject=$2 flag=$3 led=$4 restore=$5 since
	if ! $inject; then
		hil_fail "$name-inject" "could not inject: $inject"
		return
	fi
	check_flags "$name-offline-frames" "$flag=0" 3
	check_led "$name-led-blinks" "$led" blinking
	hil_check "$name-daemon-runs" daemon_alive
	since=$(hil_uptime)
	if ! $restore; then
		hil_fail "$name-restore" "could not restore: $restore"
		return
	fi
	check_recovery "$name" "$since"
	check_led "$name-led-on-again" "$led" on
}

# --- start --------------------------------------------------------------------
"$HIL_BIN/depthkeyd" --config "$DK_CONFIG" >"$DK_LOG" 2>&1 &
DK_PID=$!
check_flags daemon-frames-from-both-cameras "$ONLINE=$ONLINE" 10 --timeout 60
check_flags daemon-lecturer-keyed-by-sr2-depth "$ONLINE=$ONLINE" 3 --name /depthkey.lecturer --alpha
hil_check daemon-sr2-output-mode hil_wait 10 grep -q 'register 0x02 = 0xc0' "$SR2_LOG"
hil_check daemon-sr2-integration-time hil_wait 10 grep -q 'register 0x09 = 0x28' "$SR2_LOG"
check_led led-power-heartbeat $LED_POWER blinking
check_led led-depth-on $LED_DEPTH on
check_led led-colour-on $LED_COLOUR on
check_led led-calibration-missing $LED_CALIBRATION blinking
check_led led-error-off $LED_ERROR off

# --- SR-2 faults ----------------------------------------------------------------
sr2() { sr2_cmd "$@"; }
fault sr2-unplug "sr2 unplug" $DEPTH_OK $LED_DEPTH "sr2 replug"
fault sr2-stall "sr2 stall" $DEPTH_OK $LED_DEPTH "sr2 resume"
fault sr2-corrupt-frames "sr2 corrupt 100000" $DEPTH_OK $LED_DEPTH "sr2 corrupt 0"
fault sr2-flat-frames "sr2 flat 100000" $DEPTH_OK $LED_DEPTH "sr2 flat 0"
fault sr2-short-frames "sr2 short 100000" $DEPTH_OK $LED_DEPTH "sr2 short 0"
fault sr2-request-stalls "sr2 halt 100000" $DEPTH_OK $LED_DEPTH "sr2 halt 0"
# One bad frame is dropped, not a lost camera: depth stays online.
sr2_cmd corrupt 1
if out=$(shm_watch --until "$DEPTH_OK=0" --timeout 3); then
	hil_fail sr2-one-corrupt-frame-dropped "depth went offline for one bad frame: $out"
else
	hil_pass sr2-one-corrupt-frame-dropped "depth stayed online for 3 s"
fi

# --- webcam (vivid) faults ---------------------------------------------------
vivid() { v4l2-ctl -d /dev/video0 -c "$1=1"; }
# vivid brings a disconnected device back when its last user closes it: the
# device's return is the "reconnect" in the kernel log.
vivid_returned() { hil_wait 20 sh -c "dmesg | grep -q 'vivid-000: reconnect'"; }
colour_fault() {
	local name=$1 since
	shift
	for control in "$@"; do vivid "$control" || hil_fail "$name-inject" "v4l2-ctl -c $control=1 failed"; done
	check_flags "$name-offline-frames" "$COLOUR_OK=0" 3
	check_led "$name-led-blinks" $LED_COLOUR blinking
	hil_check "$name-daemon-runs" daemon_alive
}
dmesg -C
colour_fault webcam-disconnect disconnect
vivid_returned && since=$(dmesg | sed -n 's/^\[ *\([0-9.]*\)\] vivid-000: reconnect.*/\1/p' | tail -n1)
check_recovery webcam-disconnect "${since:-0}"
check_led webcam-disconnect-led-on-again $LED_COLOUR on
for injected in inject_vidioc_streamon_error inject_vidioc_reqbufs_error; do
	dmesg -C
	colour_fault "webcam-$injected" "$injected" disconnect
	vivid_returned && since=$(dmesg | sed -n 's/^\[ *\([0-9.]*\)\] vivid-000: reconnect.*/\1/p' | tail -n1)
	check_recovery "webcam-$injected" "${since:-0}"
done
for injected in inject_vidioc_qbuf_error inject_fatal_streaming_error; do
	since=$(hil_uptime)
	colour_fault "webcam-$injected" "$injected"
	check_recovery "webcam-$injected" "$since"
done
vivid inject_v4l2_buf_flag_error
if out=$(shm_watch --until "$COLOUR_OK=0" --timeout 3); then
	hil_fail webcam-error-buffer-dropped "colour went offline for one error buffer: $out"
else
	hil_pass webcam-error-buffer-dropped "colour stayed online for 3 s"
fi

# --- leaks over 50 unplug/replug cycles ----------------------------------------
fd_count() { local n=0 f; for f in /proc/"$DK_PID"/fd/*; do n=$((n + 1)); done; echo "$n"; }
rss_kb() { sed -n 's/^VmRSS: *\([0-9]*\) kB/\1/p' /proc/"$DK_PID"/status; }
shm_watch --until "$ONLINE=$ONLINE" --count 5 --timeout 30 >/dev/null
fds_before=$(fd_count) rss_before=$(rss_kb)
cycles=0 slow=0
for i in $(seq 50); do
	sr2_cmd unplug || break
	shm_watch --until "$DEPTH_OK=0" --timeout 20 >/dev/null || break
	since=$(hil_uptime)
	sr2_cmd replug || break
	out=$(shm_watch --until "$ONLINE=$ONLINE" --since "$since" --timeout 20) || break
	[[ $out =~ after\ ([0-9.]+)\ s ]] && echo "cycle ${BASH_REMATCH[1]}" >>"$RECOVERY_LOG"
	cycles=$i
done
shm_watch --until "$ONLINE=$ONLINE" --count 5 --timeout 30 >/dev/null
fds_after=$(fd_count) rss_after=$(rss_kb)
[ "$cycles" -eq 50 ] && hil_pass sr2-50-replug-cycles "50 cycles, each recovered" ||
	hil_fail sr2-50-replug-cycles "cycle $((cycles + 1)) did not recover"
[ "$fds_after" -eq "$fds_before" ] && hil_pass no-fd-leak "$fds_before fds before, $fds_after after" ||
	hil_fail no-fd-leak "$fds_before fds before, $fds_after after 50 cycles"
# Freed memory may stay in the allocator's pools: allow 1 MB, not 50 x a frame.
[ $((rss_after - rss_before)) -le 1024 ] && hil_pass no-memory-leak "VmRSS $rss_before kB before, $rss_after kB after" ||
	hil_fail no-memory-leak "VmRSS grew from $rss_before kB to $rss_after kB over 50 cycles"

# --- stop -------------------------------------------------------------------------
kill -TERM "$DK_PID"
wait "$DK_PID"
status=$?
[ "$status" -eq 0 ] && hil_pass daemon-clean-stop "exit status 0" || hil_fail daemon-clean-stop "exit status $status"
dark=1
for line in $LED_POWER $LED_DEPTH $LED_COLOUR $LED_CALIBRATION $LED_READER $LED_ERROR; do
	[ "$(gpio_value "$line")" = 0 ] || dark=0
done
[ "$dark" -eq 1 ] && hil_pass leds-dark-after-stop "all six lines low" || hil_fail leds-dark-after-stop "a line is still high"
