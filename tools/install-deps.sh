#!/bin/sh
# SPDX-License-Identifier: MIT
# Installs the Debian 12 packages the renderer needs, only those missing, then Intel Open Image
# Denoise (below). Idempotent: a machine that has everything runs no apt and no pip at all. Needs
# root (or sudo) when a package is missing.
set -eu
root=$(cd "$(dirname "$0")/.." && pwd)

# Build and run: OpenCL loader + headers, the CPU OpenCL driver, the scene/texture/image libraries
# (NanoVDB: header-only, for grid media's .nvdb files).
# MPI: OpenMPI (pt links it; mpirun runs it on several processes or nodes); patchelf (make bundle).
# Tests: Criterion (runner), Xvfb + Mesa (viewer tests in a real window), xdotool (window resizing).
PACKAGES="build-essential pkg-config ocl-icd-opencl-dev opencl-c-headers pocl-opencl-icd clinfo \
libtinyobjloader-dev libtinygltf-dev libstb-dev libopenexr-dev libglfw3-dev libcjson-dev libcriterion-dev \
libxml2-dev libassimp-dev libdraco-dev libnanovdb-dev \
libopenmpi-dev openmpi-bin patchelf libexpat1-dev xvfb xauth libgl1-mesa-dri xdotool python3-pip"

missing=""
for p in $PACKAGES; do
    if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
        missing="$missing $p"
    fi
done
if [ -n "$missing" ]; then
    echo "install-deps: installing:$missing"
    SUDO=""
    if [ "$(id -u)" != 0 ]; then
        if command -v sudo >/dev/null 2>&1; then SUDO=sudo; else
            echo "install-deps: missing packages:$missing; run as root (apt-get install$missing)" >&2
            exit 1
        fi
    fi
    export DEBIAN_FRONTEND=noninteractive
    $SUDO apt-get update -qq
    # shellcheck disable=SC2086
    $SUDO apt-get install -y -qq --no-install-recommends $missing >/dev/null
    echo "install-deps: done"
fi
exec "$root/tools/install-oidn.sh"
