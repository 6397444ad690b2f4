# The fault campaign (`make hil-campaign`, sourced by main.sh instead of
# daemon.sh when HIL_CAMPAIGN_FAULTS is set): the real depthkeyd on the
# virtual devices through HIL_CAMPAIGN_FAULTS faults drawn in a seeded random
# order (HIL_CAMPAIGN_SEED, bash's RANDOM: the same seed gives the same
# order), back to back, about one SR-2 fault in HIL_CAMPAIGN_OVERLAP together
# with a webcam fault (both cameras away at once). Asserted for each fault:
# the daemon runs on (a death is counted as a crash, logged, and the daemon
# started again), frames go on being published meanwhile (marked offline
# while a camera is away), and whole frames (or, for the LEDs, the lines)
# are back within 2 s of the device's return. Over the campaign: fds and
# VmRSS (its peaks) flat, from once every kind of fault has run and at least
# HIL_CAMPAIGN_WARMUP faults (what a first re-open allocates once is not a
# leak) to the end. Prints one line per fault,
# "campaign: INDEX NAME recovery SECONDS", and a summary; FAIL lines go to
# the results as in the HIL suite.

. "$here/faults.sh"
daemon_config_usable || return 0

CAMPAIGN_FAULTS=$HIL_CAMPAIGN_FAULTS
CAMPAIGN_SEED=${HIL_CAMPAIGN_SEED:?}
CAMPAIGN_OVERLAP=${HIL_CAMPAIGN_OVERLAP:-5}
CAMPAIGN_WARMUP=${HIL_CAMPAIGN_WARMUP:-10}
[ "$CAMPAIGN_WARMUP" -le $((CAMPAIGN_FAULTS / 2)) ] || CAMPAIGN_WARMUP=$((CAMPAIGN_FAULTS / 2))
CAMPAIGN_LOG=$VM_RESULTS/campaign             # INDEX NAME SECONDS (- when none)
CAMPAIGN_RESOURCES=$VM_RESULTS/campaign-resources # INDEX FDS VMRSS_KB, after each fault (FDS: fd_split's)
CAMPAIGN_SCHEDULE=$VM_RESULTS/campaign-schedule   # INDEX NAME, drawn before the first
: >"$CAMPAIGN_LOG"
: >"$CAMPAIGN_RESOURCES"

# The faults by name (campaign_run_fault runs one). An SR-2 fault drawn to
# overlap with a webcam one is named "sr2-FAULT+webcam-FAULT".
SINGLE_FAULTS="$(for f in $SR2_FAULTS; do printf 'sr2-%s ' "$f"; done)webcam-disconnect webcam-streamon-fails webcam-qbuf-error webcam-fatal-error gpio-chip-removed gpio-line-busy"
AWAY_WEBCAM_FAULTS="webcam-disconnect webcam-streamon-fails"
# words LIST INDEX: the INDEX-th (from 0) word of LIST.
word() { local -a w=($1); echo "${w[$2]}"; }
count() { local -a w=($1); echo "${#w[@]}"; }

# The webcam away: its vivid error controls, set before the disconnect.
webcam_away_controls() {
	case $1 in
	webcam-disconnect) ;;
	webcam-streamon-fails) echo inject_vidioc_streamon_error ;;
	esac
}

# Each fault function sets FAULT_MS (the recovery, empty when there was none
# to measure) and records a FAIL for whatever it found wrong.
fault_fail() { hil_fail "campaign-$FAULT_INDEX-$FAULT_NAME-$1" "$2"; }
offline_frames() { # MASK: three consecutive frames with those flags clear
	local out
	out=$(shm_watch --until "$1=0" --count 3 --timeout 30 9<&-) || fault_fail offline-frames "$out"
}

# An SR-2 fault and/or a webcam one away at once: offline frames for each
# camera gone, then both back (in a random order); the recovery is timed
# from the later return to the first whole frame.
campaign_cameras_away() { # SR2_FAULT|"" WEBCAM_FAULT|""
	local sr2=$1 webcam=$2 mask=0 sr2_back="" webcam_back_at="" since
	if [ -n "$sr2" ]; then
		sr2_inject "$sr2" || fault_fail inject "sr2_inject $sr2"
		mask=$((mask | DEPTH_OK))
	fi
	if [ -n "$webcam" ]; then
		# shellcheck disable=SC2046 # the controls are words
		webcam_away "campaign-$FAULT_INDEX-$FAULT_NAME" $(webcam_away_controls "$webcam")
		mask=$((mask | COLOUR_OK))
	fi
	offline_frames "$(printf '0x%x' "$mask")"
	recovery_watch_start
	if [ -n "$webcam" ] && [ $((RANDOM % 2)) = 0 ]; then
		webcam_back_at=$(hil_uptime)
		webcam_back
	fi
	if [ -n "$sr2" ]; then
		since=$(hil_uptime)
		SR2_RETURNED_AT=""
		sr2_restore "$sr2" || fault_fail restore "sr2_restore $sr2"
		sr2_back=${SR2_RETURNED_AT:-$since}
	fi
	if [ -n "$webcam" ] && [ -z "$webcam_back_at" ]; then
		webcam_back_at=$(hil_uptime)
		webcam_back
	fi
	since=$(printf '%s\n' $sr2_back $webcam_back_at | sort -n | tail -n1)
	if recovery_measure "$since"; then
		FAULT_MS=$RECOVERY_MS
	else
		fault_fail recovery "$RECOVERY_WHY"
	fi
}

# A failing call on the streaming webcam: the daemon notices (lost), goes on
# publishing, and re-opens it; timed from the injection to its "streaming
# again", as in the HIL suite.
campaign_webcam_error() { # CONTROL
	local lost again since out
	lost=$(lost_count v4l2-colour) again=$(again_count v4l2-colour)
	since=$(hil_uptime)
	webcam_error "campaign-$FAULT_INDEX-$FAULT_NAME" "$1"
	hil_wait 10 lost_more_than v4l2-colour "$lost" || fault_fail noticed "no 'v4l2-colour lost' within 10 s"
	# A frame published after the error was noticed (flags whatever they are).
	out=$(shm_watch --until 0=0 --timeout 10) || fault_fail frames-meanwhile "$out"
	if hil_wait 10 again_more_than v4l2-colour "$again"; then
		FAULT_MS=$(elapsed_ms "$since" "$(again_at v4l2-colour)")
	else
		fault_fail recovery "not streaming again 10 s after the error"
	fi
}

# The LEDs' chip removed (gpio-chip-removed): the daemon goes on publishing
# whole frames and lets go of all its lines (the first write that fails finds
# the chip gone). The config names the chip by its label, so when the chip is
# back, maybe as another gpiochipN (a USB GPIO expander re-plugged), the
# daemon's own retry, twice a second, looks it up and takes the lines again:
# timed from the chip's return until the daemon holds all its lines, then the
# heartbeat must blink. No reload.
# gpio-line-busy: another process holds one LED line. It takes the line
# while a reload has that LED not fitted; a reload with it fitted again gets
# the other six (the daemon goes on publishing); timed from that process
# letting go (the line's return) until the daemon holds all seven, again by
# its own retry. The lines held are the daemon's GPIO line handles (its
# other fds come and go as cameras are re-opened).
LED_KEYS="power_line depth_line colour_line calibration_line reader_line error_line board_line"
reload_and_wait() {
	local before
	before=$(reload_count)
	kill -HUP "$DK_PID"
	hil_wait 10 reloaded_more_than "$before" || gpio_fail reload "no 'configuration reloaded' within 10 s of SIGHUP"
}
whole_frames() { # WHAT
	local out
	out=$(shm_watch --until "$ONLINE=$ONLINE" --count 3 --timeout 30 9<&-) || fault_fail "$1" "$out"
}
# gpio_fail WHAT DETAIL: a FAIL, with the daemon's fds, the config's chip and
# the simulator's state in logs/campaign-gpio.log.
gpio_fail() {
	fault_fail "$1" "$2"
	{
		echo "--- fault $FAULT_INDEX $FAULT_NAME: $1 at $(hil_uptime): chip $led_chip, $(grep '^chip = ' "$DK_CONFIG")"
		ls -l /proc/"$DK_PID"/fd
		gpioinfo 2>&1
	} >>"$HIL_LOGS/campaign-gpio.log"
}
# leds_back SINCE: waits for all the daemon's lines; FAULT_MS from SINCE.
leds_back() {
	if hil_wait 10 lines_are "$LED_COUNT"; then
		FAULT_MS=$(elapsed_ms "$1" "$(hil_uptime)")
		led_shows "$LED_POWER" blinking ||
			gpio_fail heartbeat "power line $LED_SEEN after the LEDs were taken again"
	else
		gpio_fail recovery "$(lines_held) lines held 10 s after the return, not $LED_COUNT"
	fi
}
campaign_gpio_chip_removed() {
	local since
	gpio_chip_remove || { fault_fail inject "gpio-sim live=0 failed"; return; }
	whole_frames frames-without-leds
	hil_wait 5 lines_are 0 || gpio_fail lines-released "still $(lines_held) lines held 5 s after the chip went"
	since=$(hil_uptime)
	gpio_chip_return || { fault_fail restore "gpio-sim live=1 failed"; return; }
	leds_back "$since"
}
campaign_gpio_line_busy() {
	local k key line holder since
	k=$((RANDOM % LED_COUNT))
	key=$(word "$LED_KEYS" "$k") line=$(word "$LED_LINES" "$k")
	sed -i "s|^$key = .*|$key = -1|" "$DK_CONFIG"
	reload_and_wait
	hil_wait 10 lines_are $((LED_COUNT - 1)) || gpio_fail unfit "$(lines_held) lines held with $key = -1"
	gpioset --mode=signal "$led_chip" "$line=1" 9<&- &
	holder=$!
	hil_wait 10 gpio_is "$line" 1 || gpio_fail inject "gpioset could not take line $line"
	sed -i "s|^$key = .*|$key = $line|" "$DK_CONFIG"
	reload_and_wait
	lines_are $((LED_COUNT - 1)) ||
		gpio_fail other-leds "$(lines_held) lines held, expected $((LED_COUNT - 1)) with line $line busy"
	whole_frames frames-with-line-busy
	gpio_is "$line" 1 || gpio_fail line-busy "line $line is not the other user's any more"
	since=$(hil_uptime)
	kill "$holder"
	wait "$holder" 2>/dev/null
	leds_back "$since"
}

campaign_run_fault() { # NAME
	case $1 in
	sr2-*+webcam-*) campaign_cameras_away "$(echo "$1" | sed 's/^sr2-\(.*\)+.*/\1/')" "${1#*+}" ;;
	sr2-*) campaign_cameras_away "${1#sr2-}" "" ;;
	webcam-disconnect | webcam-streamon-fails) campaign_cameras_away "" "$1" ;;
	webcam-qbuf-error) campaign_webcam_error inject_vidioc_qbuf_error ;;
	webcam-fatal-error) campaign_webcam_error inject_fatal_streaming_error ;;
	gpio-chip-removed) campaign_gpio_chip_removed ;;
	gpio-line-busy) campaign_gpio_line_busy ;;
	*) fault_fail unknown "no such fault" ;;
	esac
}

# --- the schedule ----------------------------------------------------------------
RANDOM=$CAMPAIGN_SEED
n_single=$(count "$SINGLE_FAULTS")
: >"$CAMPAIGN_SCHEDULE"
for ((i = 1; i <= CAMPAIGN_FAULTS; i++)); do
	name=$(word "$SINGLE_FAULTS" $((RANDOM % n_single)))
	if [[ $name == sr2-* ]] && [ $((RANDOM % CAMPAIGN_OVERLAP)) = 0 ]; then
		name=$name+$(word "$AWAY_WEBCAM_FAULTS" $((RANDOM % $(count "$AWAY_WEBCAM_FAULTS"))))
	fi
	echo "$i $name" >>"$CAMPAIGN_SCHEDULE"
done

# --- the campaign ------------------------------------------------------------------
# The LEDs' chip by its label, which stays when the chip comes back as
# another gpiochipN.
sed -i "s|^chip = .*|chip = \"$GPIO_LABEL\"|" "$DK_CONFIG"
daemon_start
check_flags campaign-daemon-frames "$ONLINE=$ONLINE" 10 --timeout 60
crashes=0 baseline_at="" fds_start="" kinds_left=$n_single started=$(hil_uptime)
declare -A seen=()
echo "campaign: $CAMPAIGN_FAULTS faults, seed $CAMPAIGN_SEED"
while read -r FAULT_INDEX FAULT_NAME; do
	FAULT_MS=""
	campaign_run_fault "$FAULT_NAME"
	if ! daemon_alive; then
		crashes=$((crashes + 1))
		fault_fail crash "the daemon died: $(tail -n 3 "$DK_LOG" | tr '\n' ' ')"
		webcam_back
		daemon_start
	fi
	# Back to whole frames before the next fault (they follow back to back).
	out=$(shm_watch --until "$ONLINE=$ONLINE" --count 3 --timeout 30 9<&-) ||
		fault_fail whole-frames-after "$out"
	seconds=-
	if [ -n "$FAULT_MS" ]; then
		seconds=$(ms_seconds "$FAULT_MS")
		[ "$FAULT_MS" -ge 0 ] || fault_fail recovery-timing "whole frames $seconds s after the return: timed wrong"
		[ "$HIL_SANITIZER" = 1 ] || [ "$FAULT_MS" -le "$RECOVERY_LIMIT_MS" ] ||
			fault_fail recovery-time "$seconds s after the device's return (limit 2 s)"
	fi
	echo "$FAULT_INDEX $FAULT_NAME $seconds" >>"$CAMPAIGN_LOG"
	echo "$FAULT_INDEX $(fd_split | tr ' ' '+') $(rss_kb)" >>"$CAMPAIGN_RESOURCES"
	echo "campaign: $FAULT_INDEX $FAULT_NAME recovery $seconds"
	# The baseline: once every kind of fault has run, at least
	# CAMPAIGN_WARMUP faults in (or half way, if some kind never came).
	for part in ${FAULT_NAME//+/ }; do
		[ -n "${seen[$part]:-}" ] || kinds_left=$((kinds_left - 1))
		seen[$part]=1
	done
	if [ -z "$baseline_at" ] && { [ "$FAULT_INDEX" -ge "$CAMPAIGN_WARMUP" ] && [ "$kinds_left" -le 0 ] ||
		[ "$FAULT_INDEX" -ge $((CAMPAIGN_FAULTS / 2)) ]; }; then
		baseline_at=$FAULT_INDEX fds_start=$(fd_split)
		fd_names >"$VM_RESULTS/campaign-fds-start"
	fi
done <"$CAMPAIGN_SCHEDULE"
ran=$(wc -l <"$CAMPAIGN_LOG")
# The fds besides the V4L2 nodes, and at most one on each node (fd_split: a
# node is closed for a moment while its camera re-opens, so a plain count
# came out one or two over the start's, 25 -> 27, in a 14-fault campaign),
# waiting for a re-open in progress to finish.
fds_flat() {
	local others video
	read -r others video <<<"$(fd_split)"
	[ "$others" -eq "${fds_start%% *}" ] && [ "$video" -le 1 ]
}
[ -z "$fds_start" ] || hil_wait 15 fds_flat
fds_end=$(fd_split)
fd_names >"$VM_RESULTS/campaign-fds-end"
# VmRSS swings by a few MB from fault to fault (frames in flight, the
# allocator's pools): flat means its peaks do not rise. Start and end are
# the highest VmRSS over the first and the last tenth of the faults after
# the baseline (at least one each).
# shellcheck disable=SC2046 # two numbers
set -- $(awk -v from="${baseline_at:-0}" '$1 >= from { r[++n] = $3 }
	END { w = int(n / 10); if (w < 1) w = 1
		for (i = 1; i <= n; i++) { if (i <= w && r[i] > s) s = r[i]; if (i > n - w && r[i] > e) e = r[i] }
		print s + 0, e + 0 }' "$CAMPAIGN_RESOURCES")
rss_start=$1 rss_end=$2
elapsed=$(elapsed_ms "$started" "$(hil_uptime)")

# --- judged over the whole campaign ------------------------------------------------
[ "$ran" -eq "$CAMPAIGN_FAULTS" ] && hil_pass campaign-faults "$ran faults run" ||
	hil_fail campaign-faults "$ran of $CAMPAIGN_FAULTS faults run"
[ "$crashes" -eq 0 ] && hil_pass campaign-no-crash "the daemon ran through all $ran faults" ||
	hil_fail campaign-no-crash "$crashes crashes"
if [ "$crashes" -gt 0 ]; then
	hil_skip campaign-fds-flat "the daemon was restarted after a crash"
elif fds_flat; then
	hil_pass campaign-fds-flat "${fds_start%% *} fds besides the V4L2 nodes after fault $baseline_at, ${fds_end%% *} at the end, at most ${fds_end##* } on a node"
else
	hil_fail campaign-fds-flat "${fds_start%% *} fds besides the V4L2 nodes after fault $baseline_at, ${fds_end%% *} at the end, at most ${fds_end##* } on a node; new: $(comm -13 "$VM_RESULTS/campaign-fds-start" "$VM_RESULTS/campaign-fds-end" | tr '\n' ' ')"
fi
if [ "$crashes" -gt 0 ]; then
	hil_skip campaign-vmrss-flat "the daemon was restarted after a crash"
elif [ "$HIL_SANITIZER" = 1 ]; then
	hil_skip campaign-vmrss-flat "VmRSS $rss_start -> $rss_end kB not judged under ASan (quarantine)"
elif [ $((rss_end - rss_start)) -le "$LEAK_RSS_LIMIT_KB" ]; then
	hil_pass campaign-vmrss-flat "VmRSS peaks $rss_start kB after fault $baseline_at, $rss_end kB at the end"
else
	hil_fail campaign-vmrss-flat "VmRSS peaks grew from $rss_start kB to $rss_end kB (limit +$LEAK_RSS_LIMIT_KB kB)"
fi
# The recovery distribution: over all faults, then each kind.
distribution() { # prints "n N min .. median .. p99 .. max .." of stdin's seconds
	sort -n | awk '{ t[NR] = $1 }
		END { if (!NR) { print "none"; exit }
			p = int(NR * 0.99); if (p < NR * 0.99) p++
			printf "n %d min %.3f median %.3f p99 %.3f max %.3f", NR, t[1], t[int((NR + 1) / 2)], t[p], t[NR] }'
}
for kind in $(awk '{ print $2 }' "$CAMPAIGN_LOG" | sort -u); do
	echo "campaign: $kind $(awk -v k="$kind" '$2 == k && $3 != "-" { print $3 }' "$CAMPAIGN_LOG" | distribution)"
done
# shellcheck disable=SC2046 # its words
set -- $(awk '$3 != "-" { print $3 }' "$CAMPAIGN_LOG" | distribution)
echo "campaign: $ran faults, $crashes crashes, recovery min/median/p99/max ${4:-?}/${6:-?}/${8:-?}/${10:-?} s, fds start/end ${fds_start%% *}/${fds_end%% *}, VmRSS start/end $rss_start/$rss_end kB (start after fault $baseline_at), $(ms_seconds "$elapsed") s ($(awk -v e="$elapsed" -v n="$ran" 'BEGIN { printf "%.2f", n ? e / n / 1000 : 0 }') s per fault)"

daemon_stop_checks
