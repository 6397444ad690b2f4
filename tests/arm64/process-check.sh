#!/bin/sh
# `make ARCH=arm64 process-check`: the process tests of the arm64 build
# under qemu-user, when this machine can run them, else each reported
# skipped with the reason.
#
# They start build/arm64/bin/depthkeyd and the tools with execve() (and
# curl, chromium, a C compiler). qemu-user emulates one program; an arm64
# program that it runs execve()s another arm64 program through the host
# kernel, which runs it only when binfmt_misc hands aarch64 ELF files to
# qemu (qemu-user-static's /usr/lib/binfmt.d/qemu-aarch64.conf, registered
# by systemd-binfmt or update-binfmts). Without that entry every test that
# starts the daemon fails with ENOEXEC, which says nothing about the code.
# usage: process-check.sh QEMU-COMMAND... -- PROCESS-TESTS [gtest args]
set -eu
qemu=""
while [ "$1" != "--" ]; do
	qemu="$qemu $1"
	shift
done
shift
tests=$1
shift
entry=/proc/sys/fs/binfmt_misc/qemu-aarch64
if [ -r "$entry" ] && head -n 1 "$entry" | grep -qx enabled; then
	exec $qemu "$tests" "$@"
fi
count=$($qemu "$tests" --gtest_list_tests | grep -c '^  ' || true)
echo "depthkey-process-tests (arm64): all $count skipped: they execve() the arm64 daemon and tools,"
echo "  which needs a binfmt_misc entry for aarch64 ($entry) on this kernel, and there is none"
echo "  (binfmt_misc not mounted or qemu-aarch64 not registered: see docs/arm64.md)"
echo "depthkey-process-tests: 0 passed, 0 failed, $count skipped"
