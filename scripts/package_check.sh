#!/usr/bin/env bash
# `make package-check`: the .deb installed for real, in a throwaway Debian
# root (a container of the debootstrap base image, scripts/docker_base.sh):
# install with apt (its runtime dependencies from Debian), run the installed
# server from /usr/bin as the service user on the installed config, upgrade
# by reinstalling (an edited conffile stays, the world is recovered from the
# journal), remove (the journal and the config stay), purge (both go).
# Needs root and a Docker engine; CI runs the cheap half, tests/python/test_deb.py.
#   scripts/package_check.sh path/to/contactsim_<version>_amd64.deb
set -euo pipefail
cd "$(dirname "$0")/.."
DEB=$(realpath "${1:?usage: package_check.sh DEB}")
IMAGE=${BASE_IMAGE:-contactsim-base:bookworm}
bash scripts/docker_base.sh "$IMAGE"
# host network: ttl=0 multicast stays on this machine (README, troubleshooting)
docker run --rm --network host -v "$DEB:/tmp/contactsim.deb:ro" \
  -v "$PWD/scripts/package_check_inside.sh:/tmp/check.sh:ro" "$IMAGE" bash /tmp/check.sh
