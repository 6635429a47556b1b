#!/bin/sh
# Builds the Debian package from a configured build folder and checks it the way an integrator meets it:
# the files it holds, lintian (no error or warning), and the package unpacked into a fresh root with
# `dpkg --root`, where the installed walkd prints its version and the installed unit passes
# `systemd-analyze verify`. Maintainer scripts are not run there (they would need a whole system in the
# root); packaging/try-in-chroot.sh installs the package with apt in a debootstrap chroot for that.
# Usage: check-package.sh BUILD_DIR        (CTest runs it as package.deb)
set -eu
build=$(cd "$1" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT INT TERM
status=0
fail() { echo "FAIL $*"; status=1; }

cpack --config "$build/CPackConfig.cmake" -G DEB -B "$work/out" >"$work/cpack.log" 2>&1 ||
  { cat "$work/cpack.log"; exit 1; }
deb=$(ls "$work"/out/walkthrough_*.deb)
echo "ok   cpack: $(basename "$deb") ($(du -k "$deb" | cut -f1) KiB)"

dpkg-deb -c "$deb" | awk '{print $6}' | sed 's|^\./|/|' >"$work/listing"
for path in /usr/bin/walk /usr/bin/walkd /usr/bin/walk-panel-sim /lib/systemd/system/walkd.service \
  /usr/lib/sysusers.d/walkd.conf /usr/lib/tmpfiles.d/walkd.conf /lib/udev/rules.d/70-walkd.rules \
  /etc/walkthrough/kiosk.toml /usr/share/walkthrough/kiosk/demo.toml /usr/share/walkthrough/scenes/house.toml \
  /usr/share/doc/walkthrough/copyright /usr/share/doc/walkthrough/changelog.gz \
  /usr/share/man/man1/walk.1.gz /usr/share/man/man1/walkd.1.gz /usr/share/man/man1/walk-panel-sim.1.gz; do
  grep -qx "$path" "$work/listing" || fail "package lacks $path"
done
dpkg-deb -f "$deb" Depends | grep -q "libmodbus" || fail "Depends has no shared-library dependencies (shlibdeps)"
dpkg-deb -e "$deb" "$work/control"
grep -qx /etc/walkthrough/kiosk.toml "$work/control/conffiles" || fail "kiosk.toml is not a conffile"
for script in postinst prerm postrm; do sh -n "$work/control/$script" || fail "$script: syntax"; done
[ $status -eq 0 ] && echo "ok   contents: programs, unit, sysusers, tmpfiles, udev rules, configs, man pages, conffile"

if command -v lintian >/dev/null; then
  # Errors and warnings fail; informational tags (hardening notes, no init.d script) are shown only.
  lintian --allow-root "$deb" >"$work/lintian" 2>&1 || true
  if grep -qE "^(E|W):" "$work/lintian"; then
    fail "lintian:"
    cat "$work/lintian"
  else
    echo "ok   lintian: no errors or warnings"
  fi
else
  fail "lintian is not installed (scripts/install-deps.sh installs it)"
fi

root="$work/root"
mkdir -p "$root/var/lib/dpkg/info" "$root/var/lib/dpkg/updates" "$root/usr/lib/systemd"
: >"$root/var/lib/dpkg/status"
if ! dpkg --root="$root" --force-depends --unpack "$deb" >"$work/dpkg.log" 2>&1; then
  fail "dpkg --root --unpack:"
  cat "$work/dpkg.log"
else
  version=$("$root/usr/bin/walkd" --version 2>&1) || fail "installed walkd --version: $version"
  echo "ok   installed walkd --version: $version"
  # systemd-analyze needs the system's own units (sysinit.target...) beside ours in the root.
  cp -r /usr/lib/systemd/system "$root/usr/lib/systemd/"
  [ -x /usr/bin/kill ] && cp /usr/bin/kill "$root/usr/bin/kill"
  # MANPATH: the Documentation= man page is looked up among the installed files.
  if ! out=$(MANPATH="$root/usr/share/man" systemd-analyze verify --root="$root" walkd.service 2>&1) ||
    [ -n "$out" ]; then
    fail "systemd-analyze verify of the installed unit:"
    echo "$out"
  else
    echo "ok   systemd-analyze verify of the installed walkd.service"
  fi
fi
exit $status
