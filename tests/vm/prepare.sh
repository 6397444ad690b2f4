#!/bin/bash
# Prepares the test VM: host packages, Debian's current kernel (image and
# modules, unpacked and depmod'ed), the uncompressed vmlinux for a fast PVH
# boot, and a small busybox initramfs. Idempotent: a second run only checks.
#
#   tests/vm/prepare.sh            prints the kernel release it prepared
set -euo pipefail
. "$(dirname "$0")/lib.sh"

vm_host_packages qemu-system-x86 busybox-static kmod xz-utils

kver=$(vm_kernel_release)
kdir=$(vm_kernel_dir "$kver")

if [ ! -f "$kdir/.unpacked" ]; then
	deb=$(vm_fetch_deb "linux-image-$kver")
	vm_log "unpacking $(basename "$deb")"
	rm -rf "$kdir"
	mkdir -p "$kdir/root"
	dpkg -x "$deb" "$kdir/root"
	depmod -b "$kdir/root" "$kver"
	touch "$kdir/.unpacked"
fi

# PVH boots the ELF vmlinux directly: no decompression under TCG (~2 s saved).
# vmlinuz carries it as one xz stream after the setup code.
if [ ! -f "$kdir/vmlinux" ]; then
	vmlinuz="$kdir/root/boot/vmlinuz-$kver"
	offset=$(LC_ALL=C grep -obUaP '\xfd7zXZ\x00' "$vmlinuz" | head -n1 | cut -d: -f1)
	[ -n "$offset" ] || vm_die "no xz stream in $vmlinuz"
	tail -c "+$((offset + 1))" "$vmlinuz" | xz -dc --single-stream >"$kdir/vmlinux.tmp" 2>/dev/null || true
	[ "$(head -c4 "$kdir/vmlinux.tmp" | od -An -tx1 | tr -d ' ')" = "7f454c46" ] ||
		vm_die "could not extract an ELF vmlinux from $vmlinuz"
	mv "$kdir/vmlinux.tmp" "$kdir/vmlinux"
fi

# The initramfs: busybox, the init script and the modules needed to mount the
# host's root over virtio-9p with an overlay on top.
initrd="$kdir/initramfs.cpio.gz"
if [ ! -f "$initrd" ] || [ "$VM_SRC/init" -nt "$initrd" ] || [ "$0" -nt "$initrd" ]; then
	stage=$(mktemp -d)
	trap 'rm -rf "$stage"' EXIT
	mkdir -p "$stage"/{bin,dev,proc,sys,lower,upper,newroot,modules}
	cp /bin/busybox "$stage/bin/busybox"
	ln -s busybox "$stage/bin/sh"
	cp "$VM_SRC/init" "$stage/init"
	chmod 755 "$stage/init"
	: >"$stage/modules/order"
	modprobe -a -d "$kdir/root" -S "$kver" --show-depends virtio_pci 9pnet_virtio 9p overlay |
		awk '$1 == "insmod" {print $2}' | while read -r ko; do
			name=$(basename "$ko")
			grep -qx "$name" "$stage/modules/order" && continue
			case "$ko" in
			*.xz) xz -dc "$ko" >"$stage/modules/${name%.xz}"; name=${name%.xz} ;;
			*) cp "$ko" "$stage/modules/$name" ;;
			esac
			echo "$name" >>"$stage/modules/order"
		done
	echo "$kver" >"$stage/kernel-release"
	(cd "$stage" && find . | busybox cpio -o -H newc 2>/dev/null | gzip -1) >"$initrd.tmp"
	mv "$initrd.tmp" "$initrd"
	vm_log "initramfs $(du -h "$initrd" | cut -f1) with $(wc -l <"$stage/modules/order") modules"
fi

echo "$kver" >"$VM_CACHE/kernel-release"
echo "$kver"
