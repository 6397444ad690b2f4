#!/bin/bash
# Runs the hardware-in-the-loop suite: prepares the VM (tests/vm), the
# out-of-tree modules (tests/hil/kmod) and a udev layer, boots the VM and runs
# tests/hil/guest/main.sh in it against the binaries in BIN. Prints each
# check and a closing line "hil: N passed, N failed, N skipped". Exit 0 only
# when nothing failed; a VM that cannot start is a failure, never a skip.
#
#   tests/hil/run.sh [BIN]        (default build/bin; `make hil` calls this)
#
# With HIL_CAMPAIGN_FAULTS=N and HIL_CAMPAIGN_SEED=S the same VM runs the
# fault campaign instead of the suite's daemon checks (tests/hil/guest/
# campaign.sh, `make hil-campaign`): its "campaign: " lines are shown as they
# come, its logs go to build/hil/*-campaign-results/.
set -uo pipefail
here=$(cd "$(dirname "$0")" && pwd)
tree=$(cd "$here/../.." && pwd)
bin=$(cd "${1:-$tree/build/bin}" && pwd)
campaign=${HIL_CAMPAIGN_FAULTS:-}
results=$tree/build/hil/$(basename "$(dirname "$bin")")${campaign:+-campaign}-results
start=$(date +%s)
# Recovery times and VmRSS are judged on the optimised build only: the
# sanitizer build (build/san/bin) is several times slower under TCG.
sanitizer=0
[ "$(basename "$(dirname "$bin")")" = san ] && sanitizer=1

fail_setup() {
	echo "hil: FAIL setup: $*" >&2
	echo "hil: 0 passed, 1 failed, 0 skipped"
	exit 1
}

for tool in depthkeyd depthkey-calibrate depthkey-sr2-emulator depthkey-hil-sr2-probe depthkey-hil-shm-watch; do
	[ -x "$bin/$tool" ] || fail_setup "$bin/$tool is missing (make hil builds it)"
done
"$tree/tests/vm/prepare.sh" >/dev/null || fail_setup "cannot prepare the VM kernel (tests/vm/prepare.sh)"
"$here/kmod/build.sh" >/dev/null || fail_setup "cannot build gpio-sim/dummy_hcd (tests/hil/kmod/build.sh)"
# v4l2loopback (the virtual webcam's device) from Debian's DKMS source: when
# it cannot be built, the webcam section reports skipped with the reason.
v4l2loopback_error=$("$here/kmod/v4l2loopback.sh" 2>&1 >/dev/null) && v4l2loopback_error=""
. "$tree/tests/vm/lib.sh"
vm_host_packages v4l-utils gpiod usbutils ffmpeg || fail_setup "cannot install the guest's tools"
udev=$("$tree/tests/vm/layer.sh" udev udev libsystemd-shared) || fail_setup "cannot unpack udev"
prepared=$(date +%s)

rm -rf "$results"
mkdir -p "$results"
[ -z "$v4l2loopback_error" ] ||
	echo "v4l2loopback.ko could not be built: $(echo "$v4l2loopback_error" | tail -n1)" >"$results/v4l2loopback-missing"
# The daemon in the VM runs calibrated, as a set-up box would: the mapping of
# the simulator's camera rig, which the emulated devices render, for the
# webcam's 320x180 (tests/hil/guest/faults.sh says why that size).
"$bin/depthkey-calibrate" --sim --sim-colour-size 320x180 --output "$results/calibration.toml" \
	>"$results/calibrate.log" 2>&1 ||
	fail_setup "depthkey-calibrate --sim failed: $(tail -n1 "$results/calibrate.log")"
# And in the board's geometry: a board calibration for the capture stick's
# 640x360 (the simulator's board: the geometry is what is tested, not its truth).
"$bin/depthkey-calibrate" --board --sim --board-size 640x360 --colour-size 320x180 --output "$results/board.toml" \
	>"$results/calibrate-board.log" 2>&1 ||
	fail_setup "depthkey-calibrate --board --sim failed: $(tail -n1 "$results/calibrate-board.log")"
vm_options=(--results "$results" --layer "$udev" --env "HIL_BIN=$bin" --env "HIL_SANITIZER=$sanitizer")
if [ -z "$campaign" ]; then
	"$tree/tests/vm/run.sh" "${vm_options[@]}" --timeout "${HIL_TIMEOUT:-1200}" \
		--env "HIL_SECTIONS=${HIL_SECTIONS:-all}" -- bash "$here/guest/main.sh" >"$results/console.txt" 2>&1
	vm_status=$?
else
	case $campaign${HIL_CAMPAIGN_SEED:-} in *[!0-9]*) fail_setup "HIL_CAMPAIGN_FAULTS and HIL_CAMPAIGN_SEED must be numbers" ;; esac
	[ -n "${HIL_CAMPAIGN_SEED:-}" ] || fail_setup "HIL_CAMPAIGN_SEED is not set (make hil-campaign sets it)"
	# A fault takes seconds; a minute each is a VM that hangs.
	"$tree/tests/vm/run.sh" "${vm_options[@]}" --timeout "${HIL_TIMEOUT:-$((1200 + 60 * campaign))}" \
		--env "HIL_CAMPAIGN_FAULTS=$campaign" --env "HIL_CAMPAIGN_SEED=$HIL_CAMPAIGN_SEED" \
		-- bash "$here/guest/main.sh" >"$results/console.txt" 2>&1 &
	vm_pid=$!
	tail -n +1 -f --pid="$vm_pid" "$results/console.txt" | grep --line-buffered '^campaign: '
	wait "$vm_pid"
	vm_status=$?
fi
grep '^hil: ' "$results/console.txt"
passed=$(grep -c '^PASS ' "$results/results" 2>/dev/null)
failed=$(grep -c '^FAIL ' "$results/results" 2>/dev/null)
skipped=$(grep -c '^SKIP ' "$results/results" 2>/dev/null)
if ! grep -qx END "$results/results" 2>/dev/null || [ "$vm_status" -ne 0 ] && [ "${failed:-0}" -eq 0 ]; then
	# QEMU did not start, the VM timed out or the guest script broke before
	# its end: never a pass.
	tail -n 30 "$results/console.txt" | sed 's/^/hil: console: /'
	echo "hil: FAIL suite: the VM run did not complete (status $vm_status; see $results/console.txt)"
	failed=$((${failed:-0} + 1))
fi
if [ -s "$results/recovery" ]; then
	# Recovery times: each fault, then min/median/max over the replug cycles.
	grep -v '^cycle ' "$results/recovery" | while read -r name seconds; do
		echo "hil: recovery $name $seconds s"
	done
	grep '^cycle ' "$results/recovery" | cut -d' ' -f2 | sort -n | awk '
		{ t[NR] = $1 }
		END { if (NR) printf "hil: recovery over %d replug cycles: min %.3f s, median %.3f s, max %.3f s\n",
			NR, t[1], t[int((NR + 1) / 2)], t[NR] }'
fi
end=$(date +%s)
echo "hil: setup $((prepared - start)) s, VM $((end - prepared)) s; logs in $results"
# The failures again, last: a CI log often keeps only the tail.
grep '^FAIL ' "$results/results" 2>/dev/null | sed 's/^/hil: failed: /'
echo "hil: ${passed:-0} passed, ${failed:-0} failed, ${skipped:-0} skipped"
[ "${failed:-0}" -eq 0 ]
