#!/usr/bin/env bash
# README's commands on a truly fresh Debian 12: build a minbase root with debootstrap, export this repository's
# committed HEAD into it and run README's command 1 (`bash scripts/demo.sh`) there as root, so a package
# missing from scripts/install-deps.sh fails here before a user meets it.
#
#   bash scripts/fresh-debian-check.sh [--tests] [--keep]
#
#   --tests   also run README's command 2 (`bash scripts/test.sh`) in the same root (long: both precisions).
#   --keep    leave the root in place afterwards (its path is printed) instead of deleting it.
#
# Needs root, `debootstrap` and `git` (installed here when missing) and the Debian mirror (DEBIAN_MIRROR,
# default http://deb.debian.org/debian). Between runs on one machine it keeps, under FRESH_CHECK_CACHE (default
# /var/cache/bullet-buoyancy-fresh-check): the freshly debootstrapped base root as a tarball (never anything
# installed into it later: every run starts from the bare minbase root) and apt's downloaded .deb files (a
# download cache only; what gets installed is still decided by scripts/install-deps.sh alone). Delete that
# folder to start from nothing. Exit status: 0 when the commands passed, 1 when one failed, 2 on a usage or
# setup error (not root, no debootstrap, no mirror).
set -euo pipefail
cd "$(dirname "$0")/.."
repo=$(pwd)
run_tests=0
keep=0
for arg in "$@"; do
  case "$arg" in
    --tests) run_tests=1 ;;
    --keep) keep=1 ;;
    -h|--help) sed -n '2,18p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "fresh-debian-check: unknown argument '$arg' (expected --tests, --keep or --help)" >&2; exit 2 ;;
  esac
done
if [ "$(id -u)" -ne 0 ]; then
  echo "fresh-debian-check: must run as root (debootstrap and chroot need it)" >&2
  exit 2
fi
mirror=${DEBIAN_MIRROR:-http://deb.debian.org/debian}
cache=${FRESH_CHECK_CACHE:-/var/cache/bullet-buoyancy-fresh-check}
base_tar=$cache/bookworm-minbase.tar
debs=$cache/debs
start=$SECONDS

missing=()
command -v debootstrap >/dev/null || missing+=(debootstrap)
command -v git >/dev/null || missing+=(git)
if [ ${#missing[@]} -gt 0 ]; then
  echo "== installing on this machine: ${missing[*]}"
  apt-get update -qq
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null ||
    { echo "fresh-debian-check: could not install ${missing[*]}" >&2; exit 2; }
fi

mkdir -p "$cache" "$debs/partial"
if [ ! -s "$base_tar" ]; then
  echo "== debootstrap --variant=minbase bookworm ($mirror) -> $base_tar"
  staging=$(mktemp -d "$cache/base.XXXXXX")
  if ! debootstrap --variant=minbase bookworm "$staging" "$mirror" >"$cache/debootstrap.log" 2>&1; then
    tail -20 "$cache/debootstrap.log" >&2
    rm -rf "$staging"
    echo "fresh-debian-check: debootstrap failed (log: $cache/debootstrap.log)" >&2
    exit 2
  fi
  tar -C "$staging" -cf "$base_tar.part" .
  mv "$base_tar.part" "$base_tar"
  rm -rf "$staging"
fi

root=$(mktemp -d "${TMPDIR:-/tmp}/fresh-debian.XXXXXX")
mounted=()
cleanup() {
  local i
  for ((i = ${#mounted[@]} - 1; i >= 0; i--)); do umount -l "${mounted[$i]}" 2>/dev/null || true; done
  if [ "$keep" = 1 ]; then
    echo "fresh-debian-check: the root stays at $root"
  else
    rm -rf "$root"
  fi
}
trap cleanup EXIT
echo "== fresh root $root (from $base_tar)"
tar -C "$root" -xf "$base_tar"
cp /etc/resolv.conf "$root/etc/resolv.conf"
setup_failed() {
  echo "fresh-debian-check: cannot $1 here (a container without that right?): the check did not run" >&2
  exit 2
}
mount -t proc proc "$root/proc" || setup_failed "mount /proc in the root"
mounted+=("$root/proc")
mount -t sysfs sysfs "$root/sys" || setup_failed "mount /sys in the root"
mounted+=("$root/sys")
mount --bind /dev "$root/dev" || setup_failed "bind /dev into the root"
mounted+=("$root/dev")
mount --bind "$debs" "$root/var/cache/apt/archives" || setup_failed "bind the package cache into the root"
mounted+=("$root/var/cache/apt/archives")
chroot "$root" /bin/true || setup_failed "chroot into the root"

# The committed tree of this repository, as a user's fresh checkout has it (a local export: nothing is fetched).
echo "== committed HEAD $(git -C "$repo" rev-parse --short HEAD) -> /root/BulletBuoyancy"
mkdir -p "$root/root/BulletBuoyancy"
git -C "$repo" archive --format=tar HEAD | tar -x -C "$root/root/BulletBuoyancy"

in_root() {
  chroot "$root" /usr/bin/env -i HOME=/root TERM=dumb LANG=C.UTF-8 \
    PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin \
    bash -c "cd /root/BulletBuoyancy && $1"
}
status=0
step=$SECONDS
if in_root "bash scripts/demo.sh"; then
  echo "fresh-debian-check: README command 1 (bash scripts/demo.sh) passed in $((SECONDS - step)) s"
else
  echo "fresh-debian-check: README command 1 (bash scripts/demo.sh) FAILED on a fresh Debian 12 root" >&2
  status=1
fi
if [ "$run_tests" = 1 ] && [ "$status" = 0 ]; then
  step=$SECONDS
  if in_root "bash scripts/test.sh"; then
    echo "fresh-debian-check: README command 2 (bash scripts/test.sh) passed in $((SECONDS - step)) s"
  else
    echo "fresh-debian-check: README command 2 (bash scripts/test.sh) FAILED on a fresh Debian 12 root" >&2
    status=1
  fi
fi
echo "fresh-debian-check: total $((SECONDS - start)) s"
exit $status
