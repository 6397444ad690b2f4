# Shared helpers of the QEMU test VM (sourced by the scripts in tests/vm/).
#
# Everything is cached under build/vm/ of the source tree: Debian packages
# fetched with `apt-get download`, the unpacked kernel and modules, the
# initramfs. Nothing outside build/ is written except packages that apt
# installs on the host.

VM_SRC=$(cd "$(dirname "${BASH_SOURCE[0]:-$0}")" && pwd)
VM_TREE=$(cd "$VM_SRC/../.." && pwd)
VM_CACHE=${VM_CACHE:-$VM_TREE/build/vm}
VM_DEBS=$VM_CACHE/debs

vm_log() { echo "vm: $*" >&2; }
vm_die() { echo "vm: ERROR: $*" >&2; exit 1; }

# Installs the host packages the VM needs, when missing (root only).
vm_host_packages() {
	local missing="" pkg
	for pkg in "$@"; do
		dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q 'install ok installed' ||
			missing="$missing $pkg"
	done
	[ -z "$missing" ] && return 0
	[ "$(id -u)" -eq 0 ] || vm_die "missing Debian packages:$missing (run as root or install them)"
	vm_log "installing$missing"
	DEBIAN_FRONTEND=noninteractive apt-get -o DPkg::Lock::Timeout=600 install -y -qq \
		--no-install-recommends $missing >/dev/null ||
		{ apt-get -o DPkg::Lock::Timeout=600 update -qq &&
		  DEBIAN_FRONTEND=noninteractive apt-get -o DPkg::Lock::Timeout=600 install -y -qq \
			--no-install-recommends $missing >/dev/null; } ||
		vm_die "apt-get install$missing failed"
}

# The kernel release Debian currently ships: what linux-image-amd64 depends on
# (e.g. 6.1.0-56-amd64). Security updates move it, so it is looked up every
# time; an offline machine falls back to the last one fetched.
vm_kernel_release() {
	local pkg
	pkg=$(apt-cache depends linux-image-amd64 2>/dev/null |
		sed -n 's/^ *Depends: linux-image-\([0-9].*-amd64\)$/\1/p' | head -n1)
	if [ -z "$pkg" ]; then
		apt-get -o DPkg::Lock::Timeout=600 update -qq >/dev/null 2>&1 || true
		pkg=$(apt-cache depends linux-image-amd64 2>/dev/null |
			sed -n 's/^ *Depends: linux-image-\([0-9].*-amd64\)$/\1/p' | head -n1)
	fi
	if [ -z "$pkg" ] && [ -f "$VM_CACHE/kernel-release" ]; then
		pkg=$(cat "$VM_CACHE/kernel-release")
	fi
	[ -n "$pkg" ] || vm_die "cannot tell which kernel linux-image-amd64 depends on (apt-get update?)"
	echo "$pkg"
}

# Downloads Debian package NAME, at VERSION or else at apt's candidate
# version, into the cache unless it is there already; prints the .deb's path.
vm_fetch_deb() {
	local name=$1 version=${2:-} deb
	if [ -z "$version" ]; then
		version=$(apt-cache show --no-all-versions "$name" 2>/dev/null | sed -n 's/^Version: //p' | head -n1)
	fi
	mkdir -p "$VM_DEBS"
	# Offline, or apt lists without the package: take what the cache has.
	if [ -z "$version" ]; then
		deb=$(ls -t "$VM_DEBS/${name}_"*.deb 2>/dev/null | head -n1)
		[ -n "$deb" ] || vm_die "apt knows no package $name (apt-get update?)"
		echo "$deb"
		return
	fi
	deb=$(ls "$VM_DEBS/${name}_${version//:/%3a}_"*.deb 2>/dev/null | head -n1)
	if [ -z "$deb" ]; then
		vm_log "downloading $name $version"
		(cd "$VM_DEBS" && apt-get -o APT::Sandbox::User=root download -qq "$name=$version" >/dev/null 2>&1) ||
			{ apt-get -o DPkg::Lock::Timeout=600 update -qq >/dev/null 2>&1;
			  (cd "$VM_DEBS" && apt-get -o APT::Sandbox::User=root download -qq "$name=$version" >/dev/null); } ||
			vm_die "apt-get download $name=$version failed"
		deb=$(ls "$VM_DEBS/${name}_${version//:/%3a}_"*.deb | head -n1)
	fi
	echo "$deb"
}

# Paths of one kernel release's artefacts.
vm_kernel_dir() { echo "$VM_CACHE/kernel-$1"; }
