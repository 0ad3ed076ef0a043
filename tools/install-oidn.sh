#!/bin/sh
# SPDX-License-Identifier: MIT
# install-oidn.sh: Intel Open Image Denoise 2.5.1 (what `pt render --denoise` and the viewer's D key
# use) into .oidn/lib/ of the source tree, where pt looks for it beside its build (render/denoise.c:
# <folder of pt>/../.oidn/lib). OIDN is not packaged in Debian 12 and building it needs ISPC, so we
# take the official runtime from the PyPI wheel pyoidn (pinned): libOpenImageDenoise.so.2, its core,
# the CPU device (TBB bundled) and the CUDA device (needs only the driver's libcuda.so.1). pip
# installs into a folder of its own (--target): the system Python is not touched. Idempotent: a
# tree that has this version runs no pip. pt builds and runs without OIDN (it is loaded with
# dlopen), but the tests of --denoise need it, so a failure here is an error.
set -eu
root=$(cd "$(dirname "$0")/.." && pwd)
version=2.5.1
dest=$root/.oidn
[ -f "$dest/lib/VERSION" ] && [ "$(cat "$dest/lib/VERSION")" = "$version" ] && exit 0

echo "install-oidn: installing Intel Open Image Denoise $version (pip wheel pyoidn==$version.0) into $dest"
command -v python3 >/dev/null && python3 -m pip --version >/dev/null 2>&1 || {
    echo "install-oidn: needs pip (apt-get install python3-pip)" >&2; exit 1; }
tmp=$dest.tmp
rm -rf "$tmp"
if ! python3 -m pip install --quiet --disable-pip-version-check --no-deps --no-compile --root-user-action=ignore \
        --target "$tmp" "pyoidn==$version.0"; then
    rm -rf "$tmp"
    echo "install-oidn: pip could not install pyoidn==$version.0 (offline?); pt runs without" \
         "--denoise until this succeeds (or set PT_OIDN_LIBRARY to a libOpenImageDenoise.so.2)" >&2
    exit 1
fi
# The wheel's libraries carry RPATH $ORIGIN/../lib, so they must sit in a folder named lib. Only the
# C API, its core, the CPU and CUDA devices and TBB are kept (not SYCL, HIP, Level Zero: ~50 MB).
rm -rf "$dest"
mkdir -p "$dest/lib"
for f in libOpenImageDenoise.so.2 libOpenImageDenoise_core.so.$version \
         libOpenImageDenoise_device_cpu.so.$version libOpenImageDenoise_device_cuda.so.$version \
         libtbb.so.12; do
    cp "$tmp/pyoidn/oidn/lib/$f" "$dest/lib/$f"
done
# OIDN and TBB are Apache-2.0 (github.com/RenderKit/oidn, oneapi-src/oneTBB); the wheel's packaging
# is MIT: its licence file comes along.
cp "$tmp"/pyoidn-*.dist-info/licenses/LICENSE "$dest/lib/LICENSE.pyoidn" 2>/dev/null || true
rm -rf "$tmp"
echo "$version" > "$dest/lib/VERSION"
echo "install-oidn: done ($(du -sh "$dest/lib" | cut -f1))"
