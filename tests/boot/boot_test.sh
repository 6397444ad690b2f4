#!/bin/bash
# The boot test (part of `make test`): boots the built package on systemd as
# PID 1 in the QEMU VM of tests/vm/ and checks what a box must do (see
# guest_checks.sh). The package is installed with dpkg on the VM's overlay
# over the host root just before systemd starts (systemd-init), so the boot
# itself starts depthkeyd. Prints each check and timing.
#   boot_test.sh PACKAGE.deb
set -euo pipefail
cd "$(dirname "$0")/../.."
deb=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
work=build/boot
rm -rf "$work"
mkdir -p "$work"
work=$(cd "$work" && pwd)
t0=$SECONDS

# The upgrade: the same package at a higher version whose default config
# differs, so that dpkg has to decide about the technician's changed conffile.
dpkg-deb -R "$deb" "$work/upgrade"
version=$(dpkg-deb -f "$deb" Version)
sed -i "s/^Version: .*/Version: $version+boottest1/" "$work/upgrade/DEBIAN/control"
echo "# new in $version+boottest1" >>"$work/upgrade/etc/depthkey/depthkey.toml"
(cd "$work/upgrade" && find etc usr lib -type f ! -path 'etc/*' -exec md5sum {} + >DEBIAN/md5sums)
dpkg-deb --root-owner-group -b "$work/upgrade" "$work/depthkey-upgrade.deb" >/dev/null

tests/boot/slim-dpkg-db "$deb" "$work/dpkg"
tests/vm/prepare.sh >/dev/null
echo "boot test: preparation $((SECONDS - t0)) s"

t1=$SECONDS
set +e
tests/vm/run.sh --results "$work/vm" --timeout 900 \
	--append "vm.init=$PWD/tests/boot/systemd-init boot.deb=$deb boot.dpkgdb=$work/dpkg systemd.show_status=false" \
	-- tests/boot/guest_checks.sh "$work/depthkey-upgrade.deb" >"$work/console.log" 2>&1
rc=$?
set -e
cat "$work/vm/job.log" 2>/dev/null || true
echo "boot test: VM run $((SECONDS - t1)) s (console: $work/console.log), total $((SECONDS - t0)) s"
if [ "$rc" -ne 0 ] && [ ! -s "$work/vm/job.log" ]; then
	tail -n 30 "$work/console.log" >&2
	echo "boot test: FAIL: the VM did not run the checks (exit status $rc)" >&2
fi
exit "$rc"
