#!/bin/sh
# SPDX-License-Identifier: MIT
# Re-renders the Mitsuba 3 reference images in tests/references/ from the scenes in tests/scenes/.
# Run only on purpose (`make references`): nothing else calls it, and the references are committed.
# Creates the virtualenv .venv-mitsuba (gitignored) with Mitsuba from PyPI on first use.
#   tools/make-references.sh [SCENE...]     default: every scene listed below
# Environment: MITSUBA_VARIANT (default scalar_rgb; e.g. "llvm_ad_rgb,scalar_rgb" with
# DRJIT_LIBLLVM_PATH set to a libLLVM that Dr.Jit accepts), SPP_SCALE (divides every spp: quick trials).
set -eu

cd "$(dirname "$0")/.."
. tools/mitsuba-venv.sh
# The scenes' generated files (meshes, the smoke grid, skies; not in git), as make writes them.
python3 tools/make_material_scenes.py tests/scenes
python3 tools/make_media_scenes.py tests/scenes

# scene:spp. 16 batches each (so spp must be a multiple of 16); see tests/references/README.md.
ALL="furnace:16384 textured:16384 cornell:16384 cornell-sphere:32768
     conductors:8192 glass:8192 glass-clear:8192 normalmap:16384 mix:12288 envmap:4096 envmap-diffuse:4096
     fog-room:16384 smoke:16384 liquid:32768 subsurface:65536"
SCENES="${*:-}"
SCALE="${SPP_SCALE:-1}"
mkdir -p tests/references
for entry in $ALL; do
    scene=${entry%%:*}
    spp=$((${entry#*:} / SCALE))
    if [ -n "$SCENES" ] && ! echo " $SCENES " | grep -q " $scene "; then
        continue
    fi
    "$VENV/bin/python" tools/mitsuba_reference.py "tests/scenes/$scene" "tests/references/$scene.exr" \
        --spp "$spp" --batches 16 --variant "${MITSUBA_VARIANT:-scalar_rgb}" \
        --stderr "tests/references/$scene.stderr.exr"
done
