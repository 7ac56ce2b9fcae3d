#!/usr/bin/env bash
# Runs the README's commands as a newcomer would: in a minimal Debian 12 (debootstrap
# --variant=minbase bookworm) holding nothing but a fresh clone of this repository's committed HEAD,
# as root. A machine that already has packages can hide a missing one from scripts/setup.sh; this
# cannot. Run it (as root, with debootstrap installed or installable) before landing any change to
# setup or dependencies.
#   scripts/check-fresh-debian.sh            the quick start, then setup + the whole test command
#   scripts/check-fresh-debian.sh quick      the quick start only
#   scripts/check-fresh-debian.sh 'COMMAND'  COMMAND in the clone's root
# The pristine system is kept in $PENUMBRA_FRESH_BASE (default /var/tmp/penumbra-fresh-base) and
# copied for each run; each command's wall time is printed.
set -uo pipefail
repo=$(git -C "$(dirname "$0")/.." rev-parse --show-toplevel)
base=${PENUMBRA_FRESH_BASE:-/var/tmp/penumbra-fresh-base}
run=${base}-run
quick='bash scripts/setup.sh && bash scripts/build.sh && ./build/penumbra render -o demo.png'
full='bash scripts/setup.sh && bash scripts/test.sh'
case "${1:-both}" in
  both) commands=("$quick" "$full") ;;
  quick) commands=("$quick") ;;
  *) commands=("$1") ;;
esac
[ "$(id -u)" -eq 0 ] || { echo "check-fresh-debian.sh: run as root (chroot)" >&2; exit 1; }

if [ ! -x "$base/bin/bash" ]; then
  command -v debootstrap >/dev/null || apt-get install -y -q debootstrap >/dev/null || exit 1
  mirror=$(grep -h '^URIs:' /etc/apt/sources.list.d/*.sources 2>/dev/null | grep -v security | head -n1 | awk '{print $2}')
  debootstrap --variant=minbase bookworm "$base" "${mirror:-http://deb.debian.org/debian}" >"$base.log" 2>&1 ||
    { echo "check-fresh-debian.sh: debootstrap failed, see $base.log" >&2; exit 1; }
fi

unmount() { for m in dev/pts dev proc sys; do umount "$run/$m" 2>/dev/null; done; }
status=0
for command in "${commands[@]}"; do
  unmount
  rm -rf "$run" && cp -a "$base" "$run"
  git clone -q "$repo" "$run/root/penumbra" || exit 1
  cp /etc/resolv.conf "$run/etc/resolv.conf" 2>/dev/null
  mount --bind /dev "$run/dev" && mount --bind /dev/pts "$run/dev/pts" && mount -t proc proc "$run/proc" &&
    mount -t sysfs sys "$run/sys"
  start=$(date +%s)
  chroot "$run" /usr/bin/env -i HOME=/root PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin \
    TERM=dumb /bin/bash -c "cd /root/penumbra && $command"
  rc=$?
  echo "check-fresh-debian.sh: '$command' exited $rc after $(($(date +%s) - start)) s"
  [ "$rc" -eq 0 ] || status=$rc
  unmount
done
exit "$status"
