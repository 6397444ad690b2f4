#!/bin/sh
# `make offset-trials` (issue 29 §3): N live starts of depthkeyd on the
# simulator with pairing.offset_ms = "auto", each run for SECONDS, and the
# depth offset it applied compared with the simulator's truth
# (-[sim] depth_latency_ms). Starts vary as a box's do:
#   - under a CPU share: a cgroup v1 cpu quota (CPU_QUOTA_PCT of one core)
#     when /sys/fs/cgroup/cpu is writable, and every third start beside a
#     busy loop in the same cgroup, so that frames come unevenly;
#   - colour at 25, 30 and 15 fps in turn (uneven colour frame rates);
#   - one start with its output blocked: a crashed daemon's objects left under
#     the names and a stopped reader holding them mapped;
#   - one start on a still scene (a replayed sequence whose frames are all
#     the same): too little motion, so it must apply nothing.
# Pass: within 10 ms of the truth in all but one moving start, never more
# than 30 ms away (nor none applied), and nothing applied on the still scene.
#
#   sh tests/offset/offset-trials.sh BIN BUILD [N] [SECONDS]
set -eu
bin=$1
build=$2
trials=${3:-20}
seconds=${4:-30}
quota_pct=${CPU_QUOTA_PCT:-100}
work=$(mktemp -d "${TMPDIR:-/tmp}/offset-trials.XXXXXX")
cgroup=/sys/fs/cgroup/cpu/depthkey-offset-trials.$$
children=""

cleanup() {
	for pid in $children; do
		kill -CONT "$pid" 2>/dev/null || true
		kill "$pid" 2>/dev/null || true
	done
	[ -d "$cgroup" ] && rmdir "$cgroup" 2>/dev/null || true
	rm -rf "$work"
}
trap cleanup EXIT INT TERM

config=$(RUN_SIM_PREPARE_ONLY=1 sh daemon/run-sim.sh "$bin" "$build")
truth=$(sed -n 's/^depth_latency_ms = \([0-9.]*\)$/\1/p' "$config")
[ -n "$truth" ] || { echo "offset-trials: no [sim] depth_latency_ms in $config" >&2; exit 1; }

if mkdir "$cgroup" 2>/dev/null && echo 100000 > "$cgroup/cpu.cfs_period_us" &&
	echo $((quota_pct * 1000)) > "$cgroup/cpu.cfs_quota_us"; then
	share="cgroup cpu quota ${quota_pct}% of one core"
else
	cgroup=""
	share="no cgroup (not writable): the machine's own load only"
fi

# The still scene: a short simulated sequence whose frames are all its first.
still=$work/still
"$bin/depthkey-eval" --config "$config" --sim 1 --frames 100 --method depth-only --save-sequence "$still" >/dev/null
for kind in rgb depth amplitude intensity; do
	first=$(ls "$still/$kind" | head -n 1)
	for f in "$still/$kind"/*; do
		[ "$f" = "$still/$kind/$first" ] || cp "$still/$kind/$first" "$f"
	done
done

# One config per start: its own output names (other helpers' daemons may be
# running), no preview port.
trial_config() { # N FPS STILL
	sed -e "s|\"/depthkey\\.|\"/offset-trial-$$-$1.|" \
	    -e 's|^listen = .*|listen = ""|' -e 's|^log_level = .*|log_level = "debug"|' \
	    "$config" > "$work/trial$1.toml"
	# [colour] fps is the first "fps =" line of the file.
	sed -i "0,/^fps = [0-9]*/s//fps = $2/" "$work/trial$1.toml"
	if [ "$3" = 1 ]; then
		# The replay backend for both cameras, looping the still sequence.
		awk -v still="$still" '
			/^\[/ { section = $0 }
			(section == "[colour]" || section == "[depth]") && /^backend = / { $0 = "backend = \"replay\"" }
			section == "[replay]" && /^path = / { $0 = "path = \"" still "\"" }
			{ print }' "$work/trial$1.toml" > "$work/trial$1.tmp"
		mv "$work/trial$1.tmp" "$work/trial$1.toml"
	fi
}

# Runs "$@" in the trial cgroup. exec throughout: started with &, the
# subshell's pid ($!) becomes the command's, so that kill reaches it.
in_cgroup() {
	if [ -n "$cgroup" ]; then
		exec sh -c 'echo $$ > "$0/cgroup.procs" && exec "$@"' "$cgroup" "$@"
	else
		exec "$@"
	fi
}

echo "offset-trials: $trials starts of $seconds s, truth -$truth ms, $share"
within10=0
over30=0
moving=0
still_ok=1
i=1
while [ "$i" -le "$trials" ]; do
	fps=25
	case $((i % 3)) in 1) fps=30 ;; 2) fps=15 ;; esac
	is_still=0
	[ "$i" -eq "$trials" ] && is_still=1
	blocked=0
	[ "$i" -eq 2 ] && blocked=1
	busy=0
	[ $((i % 3)) -eq 0 ] && busy=1
	trial_config "$i" "$fps" "$is_still"
	note="colour $fps fps"
	hog=""
	reader=""
	if [ "$busy" = 1 ]; then
		in_cgroup sh -c 'while :; do :; done' &
		hog=$!
		children="$children $hog"
		note="$note, busy neighbour"
	fi
	if [ "$blocked" = 1 ]; then
		# A crashed writer's objects under the names, held by a reader
		# that stopped reading.
		"$bin/depthkeyd" --config "$work/trial$i.toml" > "$work/crashed$i.log" 2>&1 &
		crashed=$!
		sleep 3
		"$bin/depthkey-shmcat" --name "/offset-trial-$$-$i.composite" --timeout 5 > /dev/null 2>&1 &
		reader=$!
		children="$children $reader"
		sleep 1
		kill -STOP "$reader" 2>/dev/null || true
		kill -KILL "$crashed" 2>/dev/null || true
		wait "$crashed" 2>/dev/null || true
		note="$note, output blocked"
	fi
	[ "$is_still" = 1 ] && note="$note, still scene"
	in_cgroup "$bin/depthkeyd" --config "$work/trial$i.toml" > "$work/trial$i.log" 2>&1 &
	daemon=$!
	children="$children $daemon"
	sleep "$seconds"
	kill -TERM "$daemon" 2>/dev/null || true
	wait "$daemon" 2>/dev/null || true
	if kill -0 "$daemon" 2>/dev/null; then
		echo "offset-trials: start $i's daemon (pid $daemon) did not stop" >&2
		exit 1
	fi
	for pid in $hog $reader; do
		kill -CONT "$pid" 2>/dev/null || true
		kill "$pid" 2>/dev/null || true
		wait "$pid" 2>/dev/null || true
	done
	rm -f /dev/shm/offset-trial-$$-$i.*
	# The last status line's offset: "depth offset measured X ms, applied Y ms[, held: ...]".
	status=$(grep -o '; depth offset [^;]*' "$work/trial$i.log" | tail -n 1 | cut -c3-)
	applied=$(echo "$status" | sed -n 's/.*applied \([-+][0-9]*\) ms.*/\1/p')
	if [ "$is_still" = 1 ]; then
		if [ -n "$applied" ]; then
			still_ok=0
			verdict="FAIL: applied on a still scene"
		else
			verdict="ok: nothing applied"
		fi
	else
		moving=$((moving + 1))
		if [ -z "$applied" ]; then
			over30=$((over30 + 1))
			verdict="FAIL: none applied"
		else
			error=$((applied + ${truth%.*}))
			[ "$error" -lt 0 ] && error=$((-error))
			if [ "$error" -le 10 ]; then
				within10=$((within10 + 1))
				verdict="ok: ${error} ms off"
			elif [ "$error" -le 30 ]; then
				verdict="${error} ms off"
			else
				over30=$((over30 + 1))
				verdict="FAIL: ${error} ms off"
			fi
		fi
	fi
	echo "start $i ($note): $status -> $verdict"
	# Why: the newest estimate (log_level = "debug" logs each, once a second).
	grep -o 'offset estimate [^;]*' "$work/trial$i.log" | tail -n 1 | sed 's/^/    last /'
	i=$((i + 1))
done
echo "offset-trials: $within10 of $moving moving starts within 10 ms of the truth, $over30 more than 30 ms away or none applied; still scene: $([ $still_ok = 1 ] && echo nothing applied || echo APPLIED)"
[ "$over30" -eq 0 ] && [ "$still_ok" = 1 ] && [ "$within10" -ge $((moving - 1)) ]
