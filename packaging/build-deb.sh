#!/bin/sh
# `make deb`: builds the Debian package (binary only, unsigned) into
# build/deb/. debian/ sits at the top of the tree because that is where
# dpkg-buildpackage and debhelper look for it.
set -eu
cd "$(dirname "$0")/.."

# One version: the daemon's --version and the package's must agree.
code=$(sed -n 's/^#define DEPTHKEY_VERSION "\(.*\)"/\1/p' daemon/version.hpp)
pkg=$(dpkg-parsechangelog -S Version)
if [ "$code" != "$pkg" ]; then
	echo "make deb: daemon/version.hpp says $code but debian/changelog says $pkg" >&2
	exit 1
fi

# An architecture as argument (make deb ARCH=arm64): a cross build with
# Debian's cross toolchain, as `dpkg-buildpackage -a ARCH` sets it up (the
# DEB_HOST_* variables), with the profile that takes the OpenCV libraries
# instead of the -dev packages that cannot sit beside this machine's.
if [ -n "${1:-}" ]; then
	eval "$(dpkg-architecture -a "$1" -s)"
	export DEB_BUILD_PROFILES="cross pkg.depthkey.cross-opencv"
	# The tests are not run by the package build anyway (debian/rules).
	export DEB_BUILD_OPTIONS="nocheck ${DEB_BUILD_OPTIONS:-}"
	export CC="$DEB_HOST_GNU_TYPE-gcc" CXX="$DEB_HOST_GNU_TYPE-g++"
	checkdeps="dpkg-checkbuilddeps -a $1 -P cross,pkg.depthkey.cross-opencv"
else
	checkdeps=dpkg-checkbuilddeps
fi
arch=$(dpkg-architecture -qDEB_HOST_ARCH)
mkdir -p build/deb
# What `dpkg-buildpackage -b -us -uc` does, less the .buildinfo/.changes that
# it can only write next to the source tree (..): nothing is uploaded.
# dh_builddeb --destdir (debian/rules) puts the .deb into build/deb/.
# Each step says what it does (issue 30: the build is minutes of silence
# otherwise); its output goes to the log, shown when it fails.
log=build/deb/build.log
: >"$log"
step() {
	what=$1
	shift
	echo "make deb: $what"
	echo "=== $what: $*" >>"$log"
	"$@" >>"$log" 2>&1 || {
		tail -40 "$log" >&2
		echo "make deb: $what failed, full log in $log" >&2
		exit 1
	}
}
echo "make deb: depthkey $pkg for $arch, log in $log"
step "checking the build dependencies (debian/control)" $checkdeps
step "cleaning the package build's folders" debian/rules clean
step "compiling in build/deb/ with Debian's hardening flags (a few minutes on 2 cores)" \
	env DEB_BUILD_OPTIONS="parallel=2 ${DEB_BUILD_OPTIONS:-}" debian/rules build
step "installing into debian/depthkey/ and making the .deb" \
	env DEB_BUILD_OPTIONS="parallel=2 ${DEB_BUILD_OPTIONS:-}" debian/rules binary
deb="build/deb/depthkey_${pkg}_${arch}.deb"
test -f "$deb"
echo "make deb: wrote $deb ($(du -h "$deb" | cut -f1))"
echo "$deb"
