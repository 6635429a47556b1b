#!/bin/sh
# Checks walkd.service and walkd.sysusers the way systemd will read them. `systemd-analyze verify` prints
# warnings (unknown keys, bad values) yet exits 0, so ANY output counts as failure here.
# The unit is verified inside a temporary root holding the real system units (for sysinit.target and
# friends), this unit at /etc/systemd/system and walkd at /usr/bin, so ExecStart is checked as installed.
# Usage: verify-unit.sh [path/to/built/walkd|""] [drop-in.conf]
#   without walkd, a stand-in executable is used; a drop-in (walkd --print-unit-dropin) is verified with it.
set -eu
here=$(cd "$(dirname "$0")" && pwd)
root=$(mktemp -d)
trap 'rm -rf "$root"' EXIT INT TERM

mkdir -p "$root/usr/bin" "$root/etc/systemd/system" "$root/usr/lib/systemd" "$root/usr/lib/sysusers.d"
cp -r /usr/lib/systemd/system "$root/usr/lib/systemd/"
cp "$here/walkd.service" "$root/etc/systemd/system/walkd.service"
cp "$here/walkd.sysusers" "$root/usr/lib/sysusers.d/walkd.conf"
if [ -n "${2:-}" ]; then
  mkdir -p "$root/etc/systemd/system/walkd.service.d"
  cp "$2" "$root/etc/systemd/system/walkd.service.d/devices.conf"
fi
if [ -n "${1:-}" ]; then
  cp "$1" "$root/usr/bin/walkd"
else
  printf '#!/bin/sh\nexit 0\n' > "$root/usr/bin/walkd"
fi
chmod 755 "$root/usr/bin/walkd"
# ExecReload uses procps' /usr/bin/kill; slim images may lack it, and only its path matters here.
if [ -x /usr/bin/kill ]; then cp /usr/bin/kill "$root/usr/bin/kill"; else printf '#!/bin/sh\n' > "$root/usr/bin/kill"; fi
chmod 755 "$root/usr/bin/kill"

status=0
check() {  # check NAME COMMAND...: fails on a non-zero exit or on any output
  name=$1
  shift
  if ! out=$("$@" 2>&1) || [ -n "$out" ]; then
    echo "FAIL $name:"
    echo "$out"
    status=1
  else
    echo "ok   $name"
  fi
}
# --man=no: the Documentation= man page is installed by the package, not here (check-package.sh checks it).
check "systemd-analyze verify walkd.service" systemd-analyze verify --man=no --root="$root" walkd.service
# sysusers logs what it would create on stderr: accept exactly that, and require the walkd user.
if ! out=$(systemd-sysusers --root="$root" --dry-run 2>&1) ||
  echo "$out" | grep -qvE "^(Creating (group|user) 'walkd'|Would write /etc/)" ||
  ! echo "$out" | grep -q "Creating user 'walkd'"; then
  echo "FAIL systemd-sysusers walkd.conf:"
  echo "$out"
  status=1
else
  echo "ok   systemd-sysusers walkd.conf"
fi
# Sandboxing must stay tight: exposure 0..100 (10 = 1.0 in the table); walkd.service scores about 20.
if ! out=$(systemd-analyze security --offline=true --root="$root" --threshold=30 walkd.service 2>&1); then
  echo "FAIL systemd-analyze security (exposure above 3.0):"
  echo "$out" | tail -5
  status=1
else
  echo "ok   systemd-analyze security: $(echo "$out" | tail -1)"
fi
exit $status
