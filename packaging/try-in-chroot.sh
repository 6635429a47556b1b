#!/bin/sh
# Installs the package the way an integrator does, into a fresh Debian 12 made by debootstrap: `apt install
# ./walkthrough_*.deb` (dependencies from the archive, maintainer scripts run), then from the installed files
# `walkd --version`, `walk --version`, `systemd-analyze verify walkd.service`, the walkd user, the conffile,
# and removal (no unit left running, conffile kept until purge). Needs root and the Debian archive; takes
# minutes, so it is not part of CI (packaging/check-package.sh is).
# Usage: try-in-chroot.sh walkthrough_X_amd64.deb [CHROOT_DIR (kept between runs)]
set -eu
deb=$(readlink -f "$1")
root=${2:-/tmp/walkthrough-chroot}
if [ ! -x "$root/usr/bin/apt-get" ]; then
  debootstrap --variant=minbase bookworm "$root" http://deb.debian.org/debian >"$root.debootstrap.log" 2>&1 ||
    { tail -20 "$root.debootstrap.log"; exit 1; }
fi
cp "$deb" "$root/tmp/"
name=$(basename "$deb")
in_root() { chroot "$root" /usr/bin/env -i PATH=/usr/sbin:/usr/bin:/sbin:/bin DEBIAN_FRONTEND=noninteractive "$@"; }
echo "== apt install ./$name"
in_root apt-get install -y -q "/tmp/$name" systemd man-db >"$root.apt.log" 2>&1 || { tail -30 "$root.apt.log"; exit 1; }
grep -E "^(Setting up walkthrough|Unpacking walkthrough)" "$root.apt.log"
echo "== installed programs"
in_root walkd --version
in_root walk --version
in_root walk-panel-sim --version
echo "== systemd-analyze verify /lib/systemd/system/walkd.service"
in_root systemd-analyze verify walkd.service && echo "(no output: clean)"
echo "== walkd user, conffile, man page"
in_root getent passwd walkd
in_root dpkg-query --showformat='${Conffiles}\n' --show walkthrough
in_root sh -c 'zcat /usr/share/man/man1/walkd.1.gz | head -12'
echo "== remove, then purge"
in_root apt-get remove -y -q walkthrough >/dev/null
[ -f "$root/etc/walkthrough/kiosk.toml" ] && echo "removed: /etc/walkthrough/kiosk.toml kept (a conffile)"
[ ! -e "$root/usr/bin/walkd" ] && echo "removed: /usr/bin/walkd gone"
in_root apt-get purge -y -q walkthrough >/dev/null
[ ! -e "$root/etc/walkthrough/kiosk.toml" ] && echo "purged: /etc/walkthrough/kiosk.toml gone"
