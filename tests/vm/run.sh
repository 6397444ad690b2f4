#!/bin/bash
# Boots Debian's kernel under QEMU (TCG) with the host's root shared read-only
# and runs one command in it, as root, in the current directory. The guest sees
# the host's files at their usual paths (a tmpfs overlay takes its writes);
# the results folder is shared writable at the same path on both sides.
#
#   tests/vm/run.sh [options] [--] COMMAND [ARGS...]
#     --results DIR   shared writable folder (default: a new one under build/vm/results)
#     --layer DIR     extra read-only layer over the host root (repeatable; e.g. a
#                     folder with unpacked packages the host does not have)
#     --env NAME=VAL  environment variable for the command (repeatable)
#     --timeout S     give up after S seconds (default 600)
#     --mem MB        guest memory (default 1024)
#     --smp N         guest CPUs (default 2)
#     --append ARGS   extra kernel command line
#
# The source tree is shared into the guest explicitly (see below), so a
# checkout anywhere works, also under /tmp.
# Exit status: the command's own; 124 if the timeout hit; 125 if QEMU did not
# start or the guest never ran the command (with the reason on stderr).
# The guest's console (the command's output) goes to stdout and to
# RESULTS/console.log. Prepare the kernel first with tests/vm/prepare.sh (run.sh
# calls it when the cache is empty).
set -euo pipefail
. "$(dirname "$0")/lib.sh"

results="" layers=() timeout=600 mem=1024 smp=${VM_SMP:-2} append=""
envs=()
while [ $# -gt 0 ]; do
	case "$1" in
	--results) results=$2; shift 2 ;;
	--layer) layers+=("$(cd "$2" && pwd)"); shift 2 ;;
	--env) envs+=("$2"); shift 2 ;;
	--timeout) timeout=$2; shift 2 ;;
	--mem) mem=$2; shift 2 ;;
	--smp) smp=$2; shift 2 ;;
	--append) append=$2; shift 2 ;;
	--) shift; break ;;
	-*) vm_die "unknown option $1" ;;
	*) break ;;
	esac
done
[ $# -gt 0 ] || vm_die "usage: $0 [options] [--] COMMAND [ARGS...]"

if [ -f "$VM_CACHE/kernel-release" ]; then
	kver=$(cat "$VM_CACHE/kernel-release")
else
	kver=$("$VM_SRC/prepare.sh")
fi
kdir=$(vm_kernel_dir "$kver")
[ -f "$kdir/vmlinux" ] && [ -f "$kdir/initramfs.cpio.gz" ] || kver=$("$VM_SRC/prepare.sh")
kdir=$(vm_kernel_dir "$kver")

command -v qemu-system-x86_64 >/dev/null ||
	{ echo "vm: ERROR: qemu-system-x86_64 is not installed (tests/vm/prepare.sh installs it)" >&2; exit 125; }

if [ -z "$results" ]; then
	mkdir -p "$VM_CACHE/results"
	results=$(mktemp -d "$VM_CACHE/results/run.XXXXXX")
fi
mkdir -p "$results"
results=$(cd "$results" && pwd)
rm -f "$results/exit-status"

{
	echo "# written by tests/vm/run.sh"
	echo "export PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin HOME=/root"
	echo "export VM_RESULTS=$(printf %q "$results") VM_KERNEL_RELEASE=$kver"
	for e in "${envs[@]+"${envs[@]}"}"; do echo "export $(printf %q "$e")"; done
	echo "cd $(printf %q "$PWD") || exit 125"
	printf 'exec'; printf ' %q' "$@"; echo
} >"$results/job.sh"

# The checkout (and the VM cache, when VM_CACHE lies outside it) is shared
# explicitly, wherever it lies: the guest mounts fresh tmpfs on /tmp, /run and
# /dev/shm, which would hide a clone under /tmp (the host root's view of it).
# The guest gets each as an overlay at the same path, writable and
# discarded like the rest of its root.
trees=("$VM_TREE")
case "$VM_CACHE/" in "$VM_TREE"/*) ;; *) trees+=("$(cd "$VM_CACHE" && pwd)") ;; esac
tree_list=""
tree_args=()
for i in "${!trees[@]}"; do
	case "${trees[$i]}" in *[[:space:],]*) vm_die "cannot share ${trees[$i]}: its path has a space or comma" ;; esac
	tree_list="$tree_list${tree_list:+,}${trees[$i]}"
	tree_args+=(-virtfs "local,path=${trees[$i]},mount_tag=tree$i,security_model=none,readonly=on,multidevs=remap")
done

layer_args=()
for i in "${!layers[@]}"; do
	layer_args+=(-virtfs "local,path=${layers[$i]},mount_tag=layer$i,security_model=none,readonly=on,multidevs=remap")
done

# TCG only: KVM is not usable on this machine class. -nodefaults: no NIC,
# no VGA, no floppy; the console is the first serial port on stdout.
set +e
timeout --foreground -k 10 "$timeout" qemu-system-x86_64 \
	-accel tcg -M pc -cpu "${VM_CPU:-max}" -smp "$smp" -m "$mem" \
	-nodefaults -no-reboot -display none -monitor none -serial stdio \
	-kernel "$kdir/vmlinux" -initrd "$kdir/initramfs.cpio.gz" \
	-append "console=ttyS0 quiet loglevel=3 panic=-1 vm.results=$results vm.cache=$VM_CACHE vm.layers=${#layers[@]} vm.trees=$tree_list $append" \
	-virtfs "local,path=/,mount_tag=hostroot,security_model=none,readonly=on,multidevs=remap" \
	-virtfs "local,path=$results,mount_tag=results,security_model=none,multidevs=remap" \
	"${tree_args[@]}" "${layer_args[@]+"${layer_args[@]}"}" \
	</dev/null 2>"$results/qemu.stderr" | tee "$results/console.log"
qemu_rc=${PIPESTATUS[0]}
set -e

if [ "$qemu_rc" -eq 124 ]; then
	echo "vm: ERROR: timeout after ${timeout}s (console: $results/console.log)" >&2
	exit 124
fi
if [ ! -f "$results/exit-status" ]; then
	echo "vm: ERROR: the guest never ran the command: QEMU exit status $qemu_rc" >&2
	sed 's/^/vm: qemu: /' "$results/qemu.stderr" >&2
	tail -n 20 "$results/console.log" | sed 's/^/vm: console: /' >&2
	exit 125
fi
exit "$(cat "$results/exit-status")"
