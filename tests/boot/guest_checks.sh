#!/bin/bash
# The boot test's checks, run inside the VM by systemd (vm-job.service, after
# multi-user.target) on a system where depthkey was installed before boot
# (tests/boot/systemd-init). Prints one line per check and each timing.
#   guest_checks.sh UPGRADE.deb
# UPGRADE.deb: the same package at a higher version whose default
# depthkey.toml differs, to see dpkg keep the technician's conffile.
set -u
upgrade=$1
passed=0 failed=0
pass() { echo "ok: $*"; passed=$((passed + 1)); }
fail() { echo "FAIL: $*"; failed=$((failed + 1)); }
check() { local what=$1; shift; if "$@"; then pass "$what"; else fail "$what"; fi; }
now() { cut -d' ' -f1 /proc/uptime; }
since() { awk -v s="$1" '{ printf "%.1f", $1 - s }' /proc/uptime; }
prop() { systemctl show -P "$1" depthkeyd.service; }
# wait_until SECONDS COMMAND...: polls (TCG makes everything slow).
wait_until() {
	local limit=$1; shift
	local end=$(($(cut -d. -f1 /proc/uptime) + limit))
	until "$@"; do
		[ "$(cut -d. -f1 /proc/uptime)" -lt "$end" ] || return 1
		sleep 0.5
	done
}
running() { [ "$(prop ActiveState)/$(prop SubState)" = active/running ]; }
config=/etc/depthkey/depthkey.toml

echo "== boot"
# The boot is finished only when this job is: report the stages so far.
mono() { awk -v us="$(systemctl show -P "$1" ${2:+"$2"})" 'BEGIN { printf "%.1f", us / 1e6 }'; }
echo "timing: kernel start -> systemd: $(mono UserspaceTimestampMonotonic) s," \
	"-> multi-user.target: $(mono ActiveEnterTimestampMonotonic multi-user.target) s"
check "depthkeyd.service is enabled (by the package's postinst)" \
	test "$(systemctl is-enabled depthkeyd.service)" = enabled
check "depthkeyd was started by the boot and is running" running
# Type=notify: active only after READY=1. multi-user.target waits for it.
start_us=$(prop ExecMainStartTimestampMonotonic)
ready_us=$(prop ActiveEnterTimestampMonotonic)
echo "timing: depthkeyd exec -> READY=1: $(awk -v a="$start_us" -v b="$ready_us" 'BEGIN { printf "%.1f", (b - a) / 1e6 }') s"
check "READY=1 reached (ActiveEnterTimestamp set)" test "${ready_us:-0}" -gt 0
status=$(prop StatusText)
echo "  STATUS: $status"
check "STATUS= names both cameras, fps and calibration" \
	bash -c '[[ "$1" == "colour "*" fps"*"; depth "*" fps"*"; output "*" fps"*calibrat* ]]' _ "$status"
out=$(systemd-analyze verify depthkeyd.service 2>&1)
check "systemd-analyze verify of the installed unit prints nothing" test -z "$out"
[ -z "$out" ] || echo "$out"
echo "  $(systemd-analyze security depthkeyd.service | tail -n1)"

echo "== user, groups, hardening"
pid=$(prop MainPID)
check "runs as user depthkey" test "$(stat -c %U /proc/$pid)" = depthkey
groups=$(awk '/^Groups:/ { $1 = ""; print }' /proc/$pid/status)
check "supplementary groups: video and depthkey-hw" \
	bash -c 'for g in video depthkey-hw; do grep -qw "$(getent group $g | cut -d: -f3)" <<<"$1" || exit 1; done' _ "$groups"
check "no capabilities" grep -q '^CapEff:[[:space:]]*0000000000000000' /proc/$pid/status
check "calibration folder /var/lib/depthkey owned by depthkey" test "$(stat -c %U:%G /var/lib/depthkey)" = depthkey:depthkey

echo "== shared memory for the depthkey group"
ls -l /dev/shm | sed 's/^/  /'
check "/dev/shm/depthkey.composite is depthkey:depthkey 0640 (the group reads frames, cannot write them)" \
	test "$(stat -c %U:%G:%a /dev/shm/depthkey.composite)" = depthkey:depthkey:640
check "/dev/shm/depthkey.composite.readers is depthkey:depthkey 0660 (the group writes only reader heartbeats)" \
	test "$(stat -c %U:%G:%a /dev/shm/depthkey.composite.readers)" = depthkey:depthkey:660
useradd --system --no-create-home --groups depthkey recorder
useradd --system --no-create-home stranger
t=$(now)
setpriv --reuid recorder --regid recorder --init-groups \
	depthkey-shmcat --frames 3 --timeout 20 >/tmp/recorder.y4m 2>/tmp/recorder.err
echo "timing: 3 frames read by the recorder: $(since "$t") s"
check "a recorder in group depthkey reads frames (y4m header + 3 frames)" \
	bash -c 'head -c 9 /tmp/recorder.y4m | grep -q YUV4MPEG2 && [ "$(grep -ao FRAME /tmp/recorder.y4m | wc -l)" -ge 3 ]'
sed 's/^/  recorder: /' /tmp/recorder.err
check "a user outside the group cannot" \
	bash -c '! setpriv --reuid stranger --regid stranger --init-groups depthkey-shmcat --frames 1 --timeout 5 >/dev/null 2>&1'

echo "== preview page on loopback only"
check "the preview page answers on 127.0.0.1:8080 (/status.json names the cameras)" \
	bash -c 'curl -s --max-time 5 http://127.0.0.1:8080/status.json | grep -q "\"v4l2-colour\""'
check "the preview listens on no other address" \
	bash -c '! ss -Hltn | awk "{ print \$4 }" | grep ":8080\$" | grep -vq "^127\.0\.0\.1:8080\$"'

echo "== journal fields"
check "journalctl -u depthkeyd DEVICE=sr2 filters by device" \
	bash -c 'out=$(journalctl -q -o cat -u depthkeyd DEVICE=sr2); grep -q "depth camera SR-2 (USB 0852:0071) not found" <<<"$out" && ! grep -q v4l2-colour <<<"$out"'

echo "== the box's own cameras, none plugged in (issue 30, docs/first-run.md)"
check "the installed config names no simulator (colour v4l2, depth sr2, board colour)" \
	bash -c '! grep -q "^backend = \"sim\"" '"$config"' && grep -q "^backend = \"v4l2\"" '"$config"' && grep -q "^backend = \"sr2\"" '"$config"' && grep -q "^backend = \"colour\"" '"$config"
check "the service runs no simulator (status.json: v4l2-colour and sr2, no sim-)" \
	bash -c 's=$(curl -s --max-time 5 http://127.0.0.1:8080/status.json); grep -q "\"sr2\"" <<<"$s" && ! grep -q "\"sim-" <<<"$s"'
journal=$(journalctl -q -o cat -u depthkeyd)
colourLine='colour camera /dev/video0 not found: plug it in, then `sudo depthkeyd --check-config /etc/depthkey/depthkey.toml`'
depthLine='depth camera SR-2 (USB 0852:0071) not found: plug it in and switch on its power supply, then `sudo depthkeyd --check-config /etc/depthkey/depthkey.toml`'
check "the journal says once: $colourLine" test "$(grep -cxF "$colourLine" <<<"$journal")" = 1
check "the journal says once: $depthLine" test "$(grep -cxF "$depthLine" <<<"$journal")" = 1
# The newest frame's flags in the ring's header (hal/depthkey_shm.h: the slot
# count in the high half of 64-bit word 1, latest_frame word 7, slots from
# byte 128, 64 bytes each: sequence and flags in word 16 + 8i, frame number in
# word 17 + 8i). The header is read in one go and parsed after: separate reads
# race the writer, whose 2 slots turn over every 40 ms, while under TCG each od
# takes tens of ms. Tried again while a slot is being written (odd sequence).
latest_flags() {
	local shm=/dev/shm/depthkey.composite try slots latest i word
	local -a q
	for ((try = 0; try < 20; try++)); do
		read -r -a q <<<"$(od -An -v -t u8 -N 640 "$shm" | tr '\n' ' ')"
		slots=$((q[1] >> 32))
		latest=${q[7]}
		for ((i = 0; i < slots && i < 8; i++)); do
			word=${q[16 + 8 * i]}
			if [ "${q[17 + 8 * i]}" = "$latest" ] && [ $((word & 1)) = 0 ]; then
				echo $((word >> 32))
				return
			fi
		done
		sleep 0.05
	done
}
flags=$(latest_flags)
check "shared memory carries NO SIGNAL: frames flow, marked neither online nor colour ok (flags ${flags:-?})" \
	bash -c '[ -n "$1" ] && [ $(( $1 & 3 )) = 0 ] && depthkey-shmcat --frames 2 --timeout 10 | head -c 9 | grep -q YUV4MPEG2' _ "$flags"
check "the preview page's setup says the colour camera is missing and what to do (status.json \"setup\")" \
	bash -c 's=$(curl -s --max-time 5 http://127.0.0.1:8080/status.json); grep -qF "\"ready\": false" <<<"$s" && grep -qF "\"next\": \"colour camera /dev/video0: plug it in" <<<"$s"'
out=$(depthkeyd --check-config "$config" 2>&1)
printf '%s\n' "$out" | sed 's/^/  check-config: /'
check "depthkeyd --check-config says the same from the shell" \
	bash -c 'grep -qF "colour camera: v4l2 /dev/video0, NOT found: plug it in" <<<"$1" && grep -qF "next: colour camera /dev/video0" <<<"$1"' _ "$out"
check "docs/first-run.md is installed" test -f /usr/share/doc/depthkey/docs/first-run.md

echo "== reload"
cp "$config" /tmp/depthkey.toml.good
t=$(now)
sed -i 's/^width = .*/width = 128/; s/^height = .*/height = 96/' "$config"
systemctl reload depthkeyd
echo "timing: systemctl reload: $(since "$t") s"
check "reload keeps the same process" test "$(prop MainPID)" = "$pid"
wait_until 20 bash -c 'depthkey-shmcat --frames 1 --timeout 10 | head -1 | grep -q " W128 H96 "'
check "reload took the new config: 128x96 frames in shared memory" test $? -eq 0
echo "colour = 12" >>"$config"
systemctl reload depthkeyd
line=$(grep -n '^colour = 12' "$config" | cut -d: -f1)
wait_until 10 bash -c "journalctl -q -u depthkeyd CONFIG_LINE=$line | grep -q 'reload refused'"
check "a broken config is refused, journal names the line (CONFIG_LINE=$line)" test $? -eq 0
check "... and the daemon runs on" bash -c "[ \"\$(systemctl show -P MainPID depthkeyd)\" = $pid ] && systemctl is-active -q depthkeyd"
cp /tmp/depthkey.toml.good "$config"
systemctl reload depthkeyd

echo "== watchdog"
mkdir -p /etc/systemd/system/depthkeyd.service.d
printf '[Service]\nEnvironment=DEPTHKEY_TEST_FAULT=hang\n' >/etc/systemd/system/depthkeyd.service.d/test-fault.conf
systemctl daemon-reload
t=$(now)
systemctl restart depthkeyd
echo "timing: systemctl restart (stop + start to READY): $(since "$t") s"
pid=$(prop MainPID)
restarts=$(prop NRestarts)
t=$(now)
systemctl kill --kill-who=main --signal=SIGUSR2 depthkeyd
wait_until 60 bash -c "p=\$(systemctl show -P MainPID depthkeyd); [ \"\$p\" != 0 ] && [ \"\$p\" != $pid ] && systemctl is-active -q depthkeyd"
check "a hung loop is killed by the watchdog and restarted" test $? -eq 0
echo "timing: hang -> restarted and READY again: $(since "$t") s (WatchdogSec=$(prop WatchdogUSec))"
check "NRestarts went up by one" test "$(prop NRestarts)" = $((restarts + 1))
check "the journal says why" bash -c 'journalctl -q -u depthkeyd | grep -q "Watchdog timeout"'
rm -r /etc/systemd/system/depthkeyd.service.d
systemctl daemon-reload

echo "== stop"
t=$(now)
systemctl stop depthkeyd
echo "timing: systemctl stop: $(since "$t") s"
check "stopped cleanly: Result=success, exit status 0" \
	bash -c '[ "$(systemctl show -P Result depthkeyd)" = success ] && [ "$(systemctl show -P ExecMainStatus depthkeyd)" = 0 ]'
systemctl start depthkeyd

echo "== the technician's first steps (issue 30)"
check "the docs are in /usr/share/doc/depthkey/docs, readable as Markdown" test -f /usr/share/doc/depthkey/docs/tools.md
check "the docs the man pages name are installed (sequences.md)" test -f /usr/share/doc/depthkey/docs/sequences.md
check "depthkey-calibrate --print-pattern writes a PDF" \
	bash -c 'depthkey-calibrate --print-pattern /tmp/pattern.pdf --paper a4 >/dev/null && [ "$(head -c 5 /tmp/pattern.pdf)" = "%PDF-" ]'

echo "== package upgrade, remove, purge"
echo "# changed by the technician" >>"$config"
t=$(now)
dpkg -i --force-confold "$upgrade" >/tmp/upgrade.log 2>&1
check "upgrade installs" test $? -eq 0
echo "timing: dpkg -i (upgrade): $(since "$t") s"
check "upgrade keeps the technician's config" grep -q "changed by the technician" "$config"
check "upgrade leaves the new default beside it (.dpkg-dist)" test -f "$config.dpkg-dist"
check "upgrade restarted the daemon" wait_until 60 running
t=$(now)
dpkg -r depthkey >/tmp/remove.log 2>&1
check "remove" test $? -eq 0
echo "timing: dpkg -r: $(since "$t") s"
check "remove stops the daemon" bash -c '! systemctl is-active -q depthkeyd' ||
	systemctl status --no-pager depthkeyd | sed 's/^/  /'
check "remove keeps the config" grep -q "changed by the technician" "$config"
t=$(now)
dpkg -P depthkey >/tmp/purge.log 2>&1
check "purge" test $? -eq 0
echo "timing: dpkg -P: $(since "$t") s"
check "purge removes /etc/depthkey and /var/lib/depthkey" bash -c '[ ! -e /etc/depthkey ] && [ ! -e /var/lib/depthkey ]'

echo "boot test: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
