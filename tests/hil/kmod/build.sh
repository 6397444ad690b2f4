#!/bin/bash
# Builds, out of tree, the kernel modules of the HIL VM that Debian's kernel
# does not ship as needed, from Debian's linux-headers-KVER and
# linux-source-6.1 of exactly the VM kernel's version (downloaded into
# build/vm/debs, unpacked under build/vm/):
# - gpio-sim.ko: Debian 12 enables neither GPIO_SIM nor GPIO_MOCKUP. From
#   gpio-sim.c, gpiolib.h and irq_sim.c, with one change: irq_to_desc() is
#   not exported to modules, so irq_sim.c calls generic_handle_irq().
# - dummy_hcd.ko: the SR-2 sends frames on bulk IN endpoint 0x88, but
#   dummy_hcd's endpoint 8 is isochronous and FunctionFS cannot present an
#   endpoint under another number. The names of endpoints 1 and 8 are swapped
#   (ep8in-bulk, ep1in-iso): the same endpoints, renumbered.
# The modules are not signed; Debian's kernel loads them (not enforced).
# They are installed into the VM kernel's updates/ folder, which depmod ranks
# before kernel/, so `modprobe dummy_hcd` in the VM loads the renumbered one.
#
#   tests/hil/kmod/build.sh     prints the folder holding the .ko files
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
. "$here/../../vm/lib.sh"

vm_host_packages gcc-12 make xz-utils
kver=$("$VM_SRC/prepare.sh")
kdir=$(vm_kernel_dir "$kver")
out="$kdir/hil-modules"
updates="$kdir/root/lib/modules/$kver/updates"
if [ -f "$out/.built" ] && [ ! "$here/build.sh" -nt "$out/.built" ] &&
	[ ! "$here/Kbuild" -nt "$out/.built" ] && [ -f "$updates/dummy_hcd.ko" ]; then
	echo "$out"
	exit 0
fi

# The image, headers and source of one kernel build share one version.
version=$(dpkg-deb -f "$(vm_fetch_deb "linux-image-$kver")" Version)
series=${kver%%-*}                      # 6.1.0
series=${series%.*}                     # 6.1
abi=${kver%-amd64}                      # 6.1.0-56

headers="$kdir/headers"
if [ ! -f "$headers/.unpacked" ]; then
	rm -rf "$headers"
	mkdir -p "$headers"
	for pkg in "linux-headers-$kver" "linux-headers-$abi-common" "linux-kbuild-$series"; do
		dpkg -x "$(vm_fetch_deb "$pkg" "$version")" "$headers"
	done
	# The headers' Makefile includes the common part by its installed path.
	sed -i "s|include /usr/src/|include $headers/usr/src/|" "$headers/usr/src/linux-headers-$kver/Makefile"
	touch "$headers/.unpacked"
fi

rm -rf "$out"
mkdir -p "$out"
vm_log "extracting gpio-sim and dummy_hcd sources from linux-source-$series $version"
dpkg-deb --fsys-tarfile "$(vm_fetch_deb "linux-source-$series" "$version")" |
	tar -xO "./usr/src/linux-source-$series.tar.xz" |
	tar -xJ -C "$out" --transform='s|.*/||' --wildcards \
		"linux-source-$series/drivers/gpio/gpio-sim.c" \
		"linux-source-$series/drivers/gpio/gpiolib.h" \
		"linux-source-$series/kernel/irq/irq_sim.c" \
		"linux-source-$series/drivers/usb/gadget/udc/dummy_hcd.c"
mv "$out/gpio-sim.c" "$out/gpio-sim-core.c"
grep -q 'handle_simple_irq(irq_to_desc(irqnum));' "$out/irq_sim.c" ||
	vm_die "irq_sim.c of $version changed: the irq_to_desc() patch no longer applies"
sed -i 's/handle_simple_irq(irq_to_desc(irqnum));/generic_handle_irq(irqnum);/' "$out/irq_sim.c"
grep -q '"ep1in-bulk"' "$out/dummy_hcd.c" && grep -q '"ep8in-iso"' "$out/dummy_hcd.c" ||
	vm_die "dummy_hcd.c of $version changed: the endpoint renumbering no longer applies"
sed -i 's/"ep1in-bulk"/"ep8in-bulk"/; s/"ep8in-iso"/"ep1in-iso"/' "$out/dummy_hcd.c"
cp "$here/Kbuild" "$out/Kbuild"

vm_log "building gpio-sim.ko and dummy_hcd.ko for $kver"
make -s -C "$headers/usr/src/linux-headers-$kver" M="$out" modules >"$out/build.log" 2>&1 ||
	{ cat "$out/build.log" >&2; vm_die "module build failed"; }
mkdir -p "$updates"
cp "$out/gpio-sim.ko" "$out/dummy_hcd.ko" "$updates/"
depmod -b "$kdir/root" "$kver"
touch "$out/.built"
echo "$out"
