#!/usr/bin/env bash
# Checks the README's promise on a minimal Debian: builds a
# `debootstrap --variant=minbase` chroot, installs the README's apt line in
# it, and runs the README's commands there with this machine's Rust
# toolchain (bind-mounted read-only) on a copy of the repository.
#
#   sudo scripts/minimal-debian.sh [CHROOT_DIR]     (default /var/tmp/tc-minbase)
#
# Run it whenever dependencies or the set-up change. Needs root, debootstrap
# and network access to a Debian mirror. The visualiser command is started
# under Xvfb only if the host offers it; `cargo test` always runs.
set -euo pipefail
root=${1:-/var/tmp/tc-minbase}
repo=$(cd "$(dirname "$0")/.." && pwd)
suite=${SUITE:-bookworm}
rust_home=${RUSTUP_HOME:-$HOME/.rustup}
cargo_home=${CARGO_HOME:-$HOME/.cargo}

command -v debootstrap >/dev/null || { echo "minimal-debian: needs debootstrap (apt-get install debootstrap)" >&2; exit 2; }
[ "$(id -u)" = 0 ] || { echo "minimal-debian: needs root (chroot, mounts)" >&2; exit 2; }

if [ ! -x "$root/usr/bin/apt-get" ]; then
    debootstrap --variant=minbase "$suite" "$root"
fi
# the README's apt line, as written there
apt_line=$(grep -m1 -E '^sudo apt-get install' "$repo/README.md" | sed 's/^sudo //')
[ -n "$apt_line" ] || { echo "minimal-debian: no 'sudo apt-get install' line in README.md" >&2; exit 2; }
chroot "$root" /bin/sh -c "apt-get update -qq && DEBIAN_FRONTEND=noninteractive $apt_line"

mounts=()
cleanup() { for m in "${mounts[@]}"; do umount -l "$m" 2>/dev/null || true; done; }
trap cleanup EXIT
bind() { mkdir -p "$2"; mount --bind "$1" "$2"; mounts+=("$2"); }
bind /proc "$root/proc"
bind /dev "$root/dev"
bind "$rust_home" "$root/opt/rustup"
mount -o remount,bind,ro "$root/opt/rustup"
mkdir -p "$root/opt/cargo"
cp -r "$cargo_home/bin" "$root/opt/cargo/" 2>/dev/null || true
[ -d "$cargo_home/registry" ] && bind "$cargo_home/registry" "$root/opt/cargo/registry"
cp /etc/resolv.conf "$root/etc/resolv.conf"

rm -rf "$root/work/tirecontact"
mkdir -p "$root/work"
git -C "$repo" archive --format=tar HEAD | (mkdir -p "$root/work/tirecontact" && tar -x -C "$root/work/tirecontact")

chroot "$root" /usr/bin/env -i HOME=/root PATH=/opt/cargo/bin:/usr/bin:/bin \
    RUSTUP_HOME=/opt/rustup CARGO_HOME=/opt/cargo CI=true \
    /bin/sh -c 'cd /work/tirecontact && cargo --version && cargo test'
echo "minimal-debian: the README's test command passed in $root ($suite, minbase)"
