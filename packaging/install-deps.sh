#!/bin/sh
# Installs the Debian packages listed in build-deps.txt (or in the lists given
# as arguments) that are not installed yet. Idempotent and silent when
# everything is present, so `make run`/`make test` can call it every time.
set -eu
[ $# -gt 0 ] || set -- "$(dirname "$0")/build-deps.txt"
missing=""
for pkg in $(cat "$@" | grep -v '^#'); do
    status=$(dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null || true)
    case "$status" in
        *"install ok installed"*) ;;
        *) missing="$missing $pkg" ;;
    esac
done
[ -z "$missing" ] && exit 0
if [ "$(id -u)" -ne 0 ]; then
    echo "depthkey: missing Debian packages:$missing" >&2
    echo "depthkey: run 'sudo make deps' (or apt-get install them) first" >&2
    exit 1
fi
echo "depthkey: installing$missing"
export DEBIAN_FRONTEND=noninteractive
# A package of another architecture (libfoo-dev:arm64, ARCH=arm64 builds)
# needs that architecture added to dpkg first (multiarch).
for arch in $(printf '%s\n' $missing | sed -n 's/.*:\([a-z0-9]*\)$/\1/p' | sort -u); do
    if [ "$arch" != "$(dpkg --print-architecture)" ] &&
        ! dpkg --print-foreign-architectures | grep -qx "$arch"; then
        dpkg --add-architecture "$arch"
    fi
done
# A fresh machine has no package lists; an old list may name versions that are gone.
apt-get update -qq
# --no-remove: installing must never take a package away (a foreign
# architecture's library that cannot sit beside the native one would).
apt-get install -y -qq --no-install-recommends --no-remove $missing >/dev/null
