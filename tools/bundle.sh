#!/bin/sh
# SPDX-License-Identifier: MIT
# bundle.sh BUILD_DIR VERSION: a relocatable dist/pt-VERSION-linux-x86_64/ (+ .tar.gz) that runs on a
# machine with only an OpenCL ICD loader and a driver: bin/ (pt and the benchmark tools, linked with
# an $ORIGIN/../lib rpath), lib/ (every shared library they link that such a machine may lack),
# scenes/ and the README. lib/ also holds Intel Open Image Denoise (below), and libmpi and its
# libraries (pt links MPI), which are all a pt run without mpirun loads; OpenMPI's runtime (mpirun,
# orted, its plugins under its install prefix) is not bundled: running under mpirun needs OpenMPI
# 4.1 installed on the machine (README).
set -eu
build=$1; version=$2
name=pt-$version-linux-x86_64
dest=dist/$name
rm -rf "$dest"
mkdir -p "$dest/bin" "$dest/lib"
cp "$build/pt" "$dest/bin/"
for tool in "$build"/tools/bench_*; do
    [ -x "$tool" ] && cp "$tool" "$dest/bin/"
done
# Libraries found on any glibc system (and the ICD loader, which must come from the host) stay out.
system='^(linux-vdso|ld-linux|libc\.|libm\.|libdl\.|libpthread\.|librt\.|libgcc_s\.|libstdc\+\+\.|libz\.|libOpenCL\.)'
for bin in "$dest"/bin/*; do
    ldd "$bin" | awk '/=> \// {print $1, $3}'
done | sort -u | while read -r soname path; do
    if ! echo "$soname" | grep -Eq "$system"; then
        cp -L "$path" "$dest/lib/$soname"
    fi
done
# A library with a RUNPATH of its own (OpenMPI's: libmpi, libopen-rte, libopen-pal point at its
# install prefix) looks for its dependencies there and not in bin/pt's rpath: point it at lib/.
for lib in "$dest"/lib/*; do
    if readelf -d "$lib" | grep -q '(RUNPATH)'; then
        command -v patchelf >/dev/null || { echo "bundle: needs patchelf (apt-get install patchelf)" >&2; exit 1; }
        patchelf --set-rpath '$ORIGIN' "$lib"
    fi
done
# Intel Open Image Denoise (--denoise): the runtime tools/install-oidn.sh keeps in .oidn/lib (its C
# API, core, CPU and CUDA devices, TBB; RPATH $ORIGIN/../lib finds each other in lib/), found by
# bin/pt in ../lib (render/denoise.h). It needs no library a bare GPU machine lacks but libcuda.
./tools/install-oidn.sh
cp .oidn/lib/lib* "$dest/lib/"
cp .oidn/lib/LICENSE.pyoidn "$dest/lib/" 2>/dev/null || true
# Debug sections out (the symbol table stays: perf and backtraces still name functions): with OIDN's
# ~50 MB of network weights the archive then fits one 64 MiB upload to a GPU machine.
strip --strip-debug "$dest"/bin/*
cp -r scenes "$dest/"
# tools/bench_efficiency.py (issue 34) runs from the bundle: its Python tools and the test scenes
mkdir -p "$dest/tools" "$dest/tests"
cp tools/*.py "$dest/tools/"
cp -r tests/scenes "$dest/tests/"
cp README.md "$dest/README.md"
tar -C dist -czf "dist/$name.tar.gz" "$name"
echo "bundle: $dest ($(du -sh "$dest" | cut -f1)), dist/$name.tar.gz"
ls "$dest/lib"
