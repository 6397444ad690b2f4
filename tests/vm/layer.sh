#!/bin/bash
# Builds a read-only overlay layer for the test VM from Debian packages that
# the host does not have installed (e.g. udev): fetched with `apt-get download`
# into build/vm/debs, unpacked into build/vm/layers/NAME, with /bin, /sbin and
# /lib moved under /usr so the layer does not hide the host's merged-/usr
# symlinks. Give the folder it prints to `tests/vm/run.sh --layer`.
#
#   tests/vm/layer.sh NAME PACKAGE...
set -euo pipefail
. "$(dirname "$0")/lib.sh"

[ $# -ge 2 ] || vm_die "usage: $0 NAME PACKAGE..."
name=$1; shift
dir=$VM_CACHE/layers/$name
stamp="$dir.packages"

debs=()
for pkg in "$@"; do debs+=("$(vm_fetch_deb "$pkg")"); done
want=$(printf '%s\n' "${debs[@]##*/}")
if [ -d "$dir" ] && [ -f "$stamp" ] && [ "$(cat "$stamp")" = "$want" ]; then
	echo "$dir"
	exit 0
fi

rm -rf "$dir" "$stamp"
mkdir -p "$dir/usr"
for deb in "${debs[@]}"; do
	dpkg-deb --fsys-tarfile "$deb" | tar -x -C "$dir"
done
for top in bin sbin lib lib64; do
	[ -d "$dir/$top" ] && [ ! -L "$dir/$top" ] || continue
	mkdir -p "$dir/usr/$top"
	cp -a "$dir/$top/." "$dir/usr/$top/"
	rm -rf "${dir:?}/$top"
done
echo "$want" >"$stamp"
vm_log "layer $name: $(du -sh "$dir" | cut -f1) from $*"
echo "$dir"
