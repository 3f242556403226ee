#!/usr/bin/env bash
# verify_unit.sh ROOT — `systemd-analyze verify` on the cubdance unit as it
# lies in ROOT (a filesystem root: a package unpacked with dpkg -x, or one
# made by --stage). verify resolves ExecStart= and the unit's dependencies
# under --root, so ROOT gets a copy of this machine's own system units
# (sysinit.target, sound.target, ...) beside ours, never over ours.
# verify prints a bad key or value as a warning and still exits 0: any
# output at all fails the check.
#   verify_unit.sh --stage ROOT UNIT BINARY   make ROOT from the unit file in
#                                             the tree and a built binary
# Exit 77 (ctest: skipped) when systemd-analyze is missing.
set -euo pipefail

if ! command -v systemd-analyze >/dev/null; then
    echo "SKIP: systemd-analyze is not installed (scripts/setup.sh installs systemd)"
    exit 77
fi
if [ "${1:-}" = --stage ]; then
    root=$2 unit=$3 binary=$4
    rm -rf "$root"
    mkdir -p "$root/lib/systemd/system" "$root/usr/bin"
    cp "$unit" "$root/lib/systemd/system/cubdance.service"
    cp "$binary" "$root/usr/bin/cubdance-pi"
else
    root=$1
fi
unit_file="$root/lib/systemd/system/cubdance.service"
[ -f "$unit_file" ] || { echo "FAIL: $unit_file: no unit in the root"; exit 1; }
cp -rn /lib/systemd/system/. "$root/lib/systemd/system/"

out=$(systemd-analyze verify --root="$root" cubdance.service 2>&1) && rc=0 || rc=$?
if [ "$rc" != 0 ] || [ -n "$out" ]; then
    echo "FAIL: systemd-analyze verify on $unit_file (exit $rc):"
    echo "$out"
    exit 1
fi
# What verify cannot know but the box needs: no root, no network, the config.
for want in '^User=cubdance$' '^PrivateNetwork=yes$' '^CapabilityBoundingSet=$' \
            '^ExecStart=/usr/bin/cubdance-pi --config /etc/cubdance/cubdance.conf' \
            '^Restart=on-failure$' '^WantedBy=multi-user.target$'; do
    grep -qE "$want" "$unit_file" || { echo "FAIL: $unit_file: no line matching $want"; exit 1; }
done
echo "unit: systemd-analyze verify clean: $unit_file"
