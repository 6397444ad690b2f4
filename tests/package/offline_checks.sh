#!/bin/sh
# Offline checks of the built package, on the host (part of `make test`):
#   1. `systemd-analyze verify` of the unit prints nothing (it exits 0 even
#      on warnings, so its output is what counts);
#   2. `systemd-analyze security --offline=true` exposure <= 2.0, and IP
#      allowed with localhost only (the preview page);
#   3. lintian reports no error (its whole output is printed).
# usage: offline_checks.sh PACKAGE.deb
set -u
deb=$1
passed=0 failed=0
pass() { echo "ok: $1"; passed=$((passed + 1)); }
fail() { echo "FAIL: $1"; failed=$((failed + 1)); }

work=$(mktemp -d /tmp/depthkey-offline-XXXXXX)
trap 'rm -rf "$work"' EXIT
dpkg-deb -x "$deb" "$work/root"
unit="$work/root/lib/systemd/system/depthkeyd.service"

# verify checks that ExecStart= exists and that Documentation= pages open in
# man: point both at the unpacked package, as the host has neither.
sed "s|/usr/sbin/depthkeyd|$work/root/usr/sbin/depthkeyd|" "$unit" >"$work/depthkeyd.service"
out=$(MANPATH="$work/root/usr/share/man" systemd-analyze verify "$work/depthkeyd.service" 2>&1)
if [ -z "$out" ]; then
	pass "systemd-analyze verify depthkeyd.service: no output"
else
	printf '%s\n' "$out"
	fail "systemd-analyze verify depthkeyd.service printed the above"
fi

out=$(systemd-analyze security --offline=true "$unit" 2>&1)
score=$(printf '%s\n' "$out" | sed -n 's/.*Overall exposure level for depthkeyd.service: \([0-9.]*\).*/\1/p')
if [ -n "$score" ] && awk -v s="$score" 'BEGIN { exit !(s <= 2.0) }'; then
	pass "systemd-analyze security --offline=true: exposure $score <= 2.0"
else
	printf '%s\n' "$out" | grep -v '^✓'
	fail "systemd-analyze security --offline=true: exposure '${score:-?}' (want <= 2.0)"
fi

# The preview page listens on loopback: the unit lets IP through with
# localhost only (a LAN address needs the technician's drop-in).
if printf '%s\n' "$out" | grep -q 'IPAddressDeny=.*only localhost entries' &&
	grep -qx 'IPAddressDeny=any' "$unit" && grep -qx 'IPAddressAllow=localhost' "$unit"; then
	pass "IP traffic allowed with localhost only (IPAddressDeny=any, IPAddressAllow=localhost)"
else
	fail "the unit must deny IP but to localhost (IPAddressDeny=any, IPAddressAllow=localhost)"
fi

# lintian as root (CI) says so on stderr; that line is not a finding.
out=$(lintian --pedantic -I "$deb" 2>&1 | grep -v 'running with root privileges')
echo "lintian output (${deb##*/}):"
printf '%s\n' "${out:-(none)}" | sed 's/^/  /'
if printf '%s\n' "$out" | grep -q '^E:'; then
	fail "lintian reports errors"
else
	pass "lintian: no errors"
fi

echo "offline package checks: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
