#!/bin/bash
# The package step of `make run` on a fresh Debian 12, timed (docs/benchmarks.md,
# "The package step, measured"): a minimal Debian 12 made by debootstrap (the
# Debian package of that name; run as root), this machine's Debian sources copied
# in, then `apt-get update && apt-get install --no-install-recommends` of the
# Makefile's DEB_PACKAGES in a chroot, under /usr/bin/time -v. apt's output
# says what was downloaded and how fast; the time's figures are the CPU of
# unpacking and configuring.
#
#   sudo bash bench/package_time.sh [ROOT (default /tmp/deb12)] > log 2> time.txt
set -euo pipefail
root=${1:-/tmp/deb12}
repo=$(cd "$(dirname "$0")/.." && pwd)
packages=$(make -s -C "$repo" -f - print-packages <<'MK'
include Makefile
print-packages:
	@echo $(DEB_PACKAGES)
MK
)
[ -d "$root/etc/apt" ] || debootstrap --variant=minbase bookworm "$root" http://deb.debian.org/debian >&2
cp /etc/apt/sources.list.d/debian.sources "$root/etc/apt/sources.list.d/"
rm -f "$root/etc/apt/sources.list"
# No service starts inside the chroot.
printf '#!/bin/sh\nexit 101\n' > "$root/usr/sbin/policy-rc.d"
chmod +x "$root/usr/sbin/policy-rc.d"
mountpoint -q "$root/proc" || mount -t proc proc "$root/proc"
trap 'umount "$root/proc"' EXIT
echo "packages: $packages" >&2
/usr/bin/time -v chroot "$root" sh -c \
  "apt-get update -q && DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends $packages"
