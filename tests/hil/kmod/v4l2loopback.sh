#!/bin/bash
# Builds v4l2loopback.ko for the HIL VM's kernel from Debian's
# v4l2loopback-dkms source (the package a box installs, built here as DKMS
# would, against linux-headers of exactly the VM kernel's version, which
# build.sh unpacked), unchanged, and installs it into the VM kernel's
# updates/ folder. Cached in build/vm/ like the other modules: rebuilt only
# when this script or the package version changes.
#
#   tests/hil/kmod/v4l2loopback.sh   prints the folder holding the .ko;
#                                    exit 1 with the reason on stderr
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
. "$here/../../vm/lib.sh"

kver=$("$VM_SRC/prepare.sh")
kdir=$(vm_kernel_dir "$kver")
"$here/build.sh" >/dev/null # the headers, unpacked and fixed up
headers="$kdir/headers/usr/src/linux-headers-$kver"
[ -d "$headers" ] || vm_die "no linux-headers-$kver under $kdir/headers"
out="$kdir/v4l2loopback"
updates="$kdir/root/lib/modules/$kver/updates"
deb=$(vm_fetch_deb v4l2loopback-dkms)
version=$(dpkg-deb -f "$deb" Version)
if [ -f "$out/.built-$version" ] && [ ! "$here/v4l2loopback.sh" -nt "$out/.built-$version" ] &&
	[ -f "$updates/v4l2loopback.ko" ]; then
	echo "$out"
	exit 0
fi

rm -rf "$out"
mkdir -p "$out/pkg"
dpkg-deb -x "$deb" "$out/pkg"
src=$(ls -d "$out"/pkg/usr/src/v4l2loopback-* 2>/dev/null | head -n1)
[ -n "$src" ] && [ -f "$src/v4l2loopback.c" ] || vm_die "v4l2loopback-dkms $version has no usr/src/v4l2loopback-*/v4l2loopback.c"
cp "$src"/*.c "$src"/*.h "$out/"
echo 'obj-m := v4l2loopback.o' >"$out/Kbuild"
vm_log "building v4l2loopback.ko $version for $kver"
make -s -C "$headers" M="$out" modules >"$out/build.log" 2>&1 ||
	{ tail -n 20 "$out/build.log" >&2; vm_die "v4l2loopback $version does not build against $kver"; }
mkdir -p "$updates"
cp "$out/v4l2loopback.ko" "$updates/"
depmod -b "$kdir/root" "$kver"
touch "$out/.built-$version"
echo "$out"
