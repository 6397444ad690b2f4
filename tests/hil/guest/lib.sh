# Helpers of the HIL tests inside the VM (bash, sourced). Results go to
# $VM_RESULTS/results as "PASS|FAIL|SKIP NAME: detail" lines, which the host
# side (tests/hil/run.sh) counts. Under TCG a fork costs ~16 ms and shell
# loops are slow: everything waits by polling with generous deadlines.

HIL_RESULTS=$VM_RESULTS/results
HIL_LOGS=$VM_RESULTS/logs
mkdir -p "$HIL_LOGS"

hil_record() { # STATUS NAME DETAIL...
	local status=$1 name=$2
	shift 2
	echo "$status $name: $*" >>"$HIL_RESULTS"
	echo "hil: $status $name: $* [at $(hil_uptime) s]"
}
hil_pass() { hil_record PASS "$@"; }
hil_fail() { hil_record FAIL "$@"; }
hil_skip() { hil_record SKIP "$@"; }

# Centiseconds since boot, without a fork.
hil_now_cs() {
	local up
	read -r up _ </proc/uptime
	echo $((10#${up/./}))
}
# Seconds since boot as in /proc/uptime, e.g. 12.34.
hil_uptime() {
	local up
	read -r up _ </proc/uptime
	echo "$up"
}

# hil_sleep SECONDS: sleeps without a fork (a read that times out on a FIFO
# nobody writes to), so polling loops cost the VM little.
mkfifo /run/hil-sleep 2>/dev/null
exec 8<>/run/hil-sleep
hil_sleep() { read -r -t "$1" -u 8 _ || :; }

# hil_wait SECONDS CMD...: polls CMD every 0.1 s until it succeeds; fails
# after SECONDS.
hil_wait() {
	local deadline=$(($(hil_now_cs) + $1 * 100))
	shift
	while ! "$@" >/dev/null 2>&1; do
		[ "$(hil_now_cs)" -lt "$deadline" ] || return 1
		hil_sleep 0.1
	done
}

# hil_check NAME CMD...: PASS when CMD succeeds, FAIL with its output if not.
hil_check() {
	local name=$1 out
	shift
	if out=$("$@" 2>&1); then
		hil_pass "$name" "$(echo "$out" | tail -n1)"
	else
		hil_fail "$name" "$(echo "$out" | tail -n3 | tr '\n' ' ')"
	fi
}

# hil_section NAME: true when HIL_SECTIONS (space-separated, default "all")
# selects that part of the suite, for quicker runs while debugging.
hil_section() {
	[ "${HIL_SECTIONS:-all}" = all ] || [[ " $HIL_SECTIONS " == *" $1 "* ]]
}

# Prefixes each line of stdin with the uptime, without a fork per line.
hil_timestamp() {
	local line up
	while IFS= read -r line; do
		read -r up _ </proc/uptime
		echo "[$up] $line"
	done
}

# --- the emulated SR-2 ------------------------------------------------------
SR2_FIFO=/run/sr2.ctl
SR2_LOG=$HIL_LOGS/sr2-emulator.log

sr2_start() {
	"$HIL_BIN/depthkey-sr2-emulator" --control "$SR2_FIFO" --seed 7 --max-fps 15 2>&1 |
		hil_timestamp >>"$SR2_LOG" &
	hil_wait 20 grep -q 'plugged into' "$SR2_LOG" && SR2_PID=$(pidof depthkey-sr2-emulator)
}

# sr2_cmd COMMAND: sends a command and waits for its acknowledgement.
sr2_cmd() {
	local before
	kill -0 "$SR2_PID" 2>/dev/null || { echo "sr2 emulator is not running" >&2; return 1; }
	before=$(grep -c "] sr2-emulator: \(ok\|error\) " "$SR2_LOG")
	echo "$*" >"$SR2_FIFO"
	hil_wait 10 sr2_answered "$before" || return 1
	tail -n 5 "$SR2_LOG" | grep -q "] sr2-emulator: ok $*$"
}

sr2_answered() { [ "$(grep -c "] sr2-emulator: \(ok\|error\) " "$SR2_LOG")" -gt "$1" ]; }
# sr2_replug: plugs the camera back in; sets SR2_RETURNED_AT to the uptime at
# which the host had configured it (enumeration done: the device is back),
# as the emulator says (the log's own timestamps may lag in a busy VM).
sr2_replug() {
	local before
	before=$(grep -c 'host configured the device' "$SR2_LOG")
	sr2_cmd replug &&
		hil_wait 20 sr2_configured "$before" &&
		SR2_RETURNED_AT=$(grep 'host configured the device' "$SR2_LOG" | tail -n1 | sed 's/.* at \([0-9.]*\)$/\1/')
}
sr2_configured() { [ "$(grep -c 'host configured the device' "$SR2_LOG")" -gt "$1" ]; }
sr2_present() { lsusb -d 0852:0071; }
sr2_absent() { ! lsusb -d 0852:0071; }

# --- gpio-sim ---------------------------------------------------------------
GPIO_SIM=/sys/kernel/config/gpio-sim/hil-leds

# Creates a simulated chip of 8 lines; prints its name (gpiochipN).
# The bank's label: a name that stays when the chip comes back as a new
# gpiochipN (the LED config can name a chip by its label).
GPIO_LABEL=depthkey-hil-leds
gpio_sim_create() {
	mkdir -p "$GPIO_SIM/bank0" &&
		echo 8 >"$GPIO_SIM/bank0/num_lines" &&
		echo "$GPIO_LABEL" >"$GPIO_SIM/bank0/label" &&
		echo 1 >"$GPIO_SIM/live" &&
		cat "$GPIO_SIM/bank0/chip_name"
}

# gpio_value LINE: the level the line's user drives, read from the simulator.
gpio_value() {
	local v
	read -r v <"/sys/devices/platform/$(cat "$GPIO_SIM/dev_name")/$(cat "$GPIO_SIM/bank0/chip_name")/sim_gpio$1/value"
	echo "$v"
}

gpio_is() { [ "$(gpio_value "$1")" = "$2" ]; }

# gpio_pattern LINE CENTISECONDS: samples the line for that long and prints
# "on", "off" or "blinking" (both levels seen).
gpio_pattern() {
	local path deadline v ones=0 zeros=0
	path="/sys/devices/platform/$(cat "$GPIO_SIM/dev_name")/$(cat "$GPIO_SIM/bank0/chip_name")/sim_gpio$1/value"
	deadline=$(($(hil_now_cs) + $2))
	while [ "$(hil_now_cs)" -lt "$deadline" ]; do
		read -r v <"$path"
		if [ "$v" = 1 ]; then ones=$((ones + 1)); else zeros=$((zeros + 1)); fi
		hil_sleep 0.02
	done
	if [ "$ones" -gt 0 ] && [ "$zeros" -gt 0 ]; then echo blinking
	elif [ "$ones" -gt 0 ]; then echo on
	else echo off; fi
}
