#!/usr/bin/env bash
# Makes the base image of docker/Dockerfile, a minimal Debian bookworm, from
# debootstrap and `docker import`, since no image registry is reachable from
# our machines (docs/packaging.md, "Docker"). Does nothing when the image
# is there already.
#   scripts/docker_base.sh [IMAGE]        (default contactsim-base:bookworm)
#   DEBIAN_MIRROR=http://... for another mirror than deb.debian.org
set -euo pipefail
IMAGE=${1:-contactsim-base:bookworm}
MIRROR=${DEBIAN_MIRROR:-http://deb.debian.org/debian}
if docker image inspect "$IMAGE" >/dev/null 2>&1; then
  echo "docker-base: $IMAGE is there"
  exit 0
fi
command -v debootstrap >/dev/null || { echo "docker-base: needs debootstrap (apt-get install debootstrap)" >&2; exit 1; }
root=$(mktemp -d /var/tmp/contactsim-rootfs.XXXXXX)
trap 'rm -rf "$root"' EXIT
echo "docker-base: debootstrap bookworm into $root (a few minutes)"
debootstrap --variant=minbase bookworm "$root" "$MIRROR" >"$root.log" 2>&1 \
  || { tail -20 "$root.log" >&2; exit 1; }
rm -f "$root.log"
# the updates and security suites, as on a stock bookworm image
cat >"$root/etc/apt/sources.list" <<SOURCES
deb $MIRROR bookworm main
deb $MIRROR bookworm-updates main
deb ${MIRROR%/debian}/debian-security bookworm-security main
SOURCES
# this machine's CA bundle, so that apt over https and pip trust what the
# machine trusts (minbase has no ca-certificates package)
if [ -f /etc/ssl/certs/ca-certificates.crt ]; then
  mkdir -p "$root/etc/ssl/certs"
  cp /etc/ssl/certs/ca-certificates.crt "$root/etc/ssl/certs/"
fi
# no package caches or lists in the image; the Dockerfile's stages update
chroot "$root" apt-get clean
rm -rf "$root"/var/lib/apt/lists/* "$root"/var/cache/apt/*.bin
tar -C "$root" --numeric-owner -c . | docker import -c 'CMD ["/bin/bash"]' - "$IMAGE" >/dev/null
echo "docker-base: $IMAGE $(docker image inspect -f '{{.Size}}' "$IMAGE" | awk '{printf "%.0f MB", $1/1e6}')"
