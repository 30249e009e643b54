#!/bin/bash
# The package step of `make run` on a fresh Debian 12, timed (docs/benchmarks.md,
# "Cold build of `make run`"): a minimal Debian 12 made once by debootstrap
# (the Debian package of that name; run as root) in BASE, copied to a fresh
# ROOT for each run, this machine's Debian sources copied in. Then, in a
# chroot, each under /usr/bin/time (CPU user + sys, wall):
#   1. apt-get update;
#   2. the build's packages (the Makefile's DEB_BUILD_PACKAGES): downloaded
#      (apt-get --download-only), then installed;
#   3. the workbench's packages (DEB_APP_PACKAGES): downloaded, then installed;
# each install with the Makefile's apt-get options (APT_INSTALL), or with the
# options in $APT_OPTIONS instead when that is set (e.g. "" for apt's own).
# With --make-run, instead of 2 and 3: a fresh clone of this repository,
# copied into the chroot, runs `make run` there (its packages, its build, the
# motor's contacts; `make` itself installed first, untimed).
# DEBCACHE, when given, is bind-mounted as apt's archive folder: a second run
# finds the packages there and downloads nothing (the download is then timed
# by the first run only).
#
#   sudo bash bench/package_time.sh [--make-run] BASE ROOT [DEBCACHE] > log 2> times.txt
set -euo pipefail
make_run=0
if [ "${1:-}" = --make-run ]; then make_run=1; shift; fi
base=${1:?BASE}; root=${2:?ROOT}; debcache=${3:-}
repo=$(cd "$(dirname "$0")/.." && pwd)
print() {  # a variable of the Makefile
  make -s -C "$repo" -f - print <<MK
include Makefile
print:
	@echo \$($1)
MK
}
build_packages=$(print DEB_BUILD_PACKAGES)
app_packages=$(print DEB_APP_PACKAGES)
install=${APT_OPTIONS+env DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends $APT_OPTIONS}
install=${install:-$(print APT_INSTALL)}

[ -d "$base/etc/apt" ] || debootstrap --variant=minbase bookworm "$base" http://deb.debian.org/debian >&2
rm -rf "$root"
cp -a "$base" "$root"
cp /etc/apt/sources.list.d/debian.sources "$root/etc/apt/sources.list.d/"
rm -f "$root/etc/apt/sources.list"
cp /etc/resolv.conf "$root/etc/resolv.conf"
# No service starts inside the chroot.
printf '#!/bin/sh\nexit 101\n' > "$root/usr/sbin/policy-rc.d"
chmod +x "$root/usr/sbin/policy-rc.d"
mounts=()
bind() { mkdir -p "$root/$2"; mount --bind "$1" "$root/$2"; mounts=("$root/$2" "${mounts[@]}"); }
mount -t proc proc "$root/proc"; mounts=("$root/proc")
bind /dev dev
bind /dev/pts dev/pts
[ -n "$debcache" ] && mkdir -p "$debcache/partial" && bind "$debcache" var/cache/apt/archives
trap 'for m in "${mounts[@]}"; do umount "$m"; done' EXIT

step() {  # name, command in the chroot
  echo "== $1: $2" >&2
  /usr/bin/time -f "$1: %U s user, %S s sys, %e s wall" chroot "$root" sh -c "$2" >&2
}
echo "start $(date -u +%H:%M:%S), load $(cut -d' ' -f1-3 /proc/loadavg)" >&2
step update "apt-get update -q"
if [ $make_run = 1 ]; then
  chroot "$root" sh -c "env DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends make" >/dev/null
  rm -rf "$root/root/contacts"
  git clone -q "$repo" "$root/root/contacts"
  step make-run "cd /root/contacts && CCACHE_DISABLE=1 make run"
else
  step build-download "apt-get install -y -q --no-install-recommends --download-only $build_packages"
  step build-install "$install $build_packages"
  step app-download "apt-get install -y -q --no-install-recommends --download-only $app_packages"
  step app-install "$install $app_packages"
fi
echo "end $(date -u +%H:%M:%S), load $(cut -d' ' -f1-3 /proc/loadavg)" >&2
chroot "$root" dpkg-query -W -f '${Status}\n' | grep -c '^install ok installed' | sed 's/^/packages installed: /' >&2
