#!/bin/sh
# SPDX-License-Identifier: MIT
# bench_denoise.sh [OUT_DIR]: what --denoise gains (issue 35), as CSV on stdout (and OUT_DIR/denoise.csv):
#   scene,spp,mode,relmse,psnr    mode = noisy | denoised (albedo + normal guides) | color-only
# on three scenes at SIZE x SIZE, against a pt render of REF_SPP samples with another seed:
#   cornell  scenes/cornell-box (area light, diffuse)
#   envtex   scenes/venice's sphere and floor lit by the HDR sky, with procedural noise textures
#            on both (texture detail the denoiser must keep)
#   dof      the Cornell box through a lens (aperture 0.25, focused on the back wall: the boxes
#            blur, the guides must blur with them)
# then one line per device of the denoising time at 1920x1080:
#   timing,1920x1080,DEVICE,denoise_seconds,guide_pass_seconds,guide_spp
# relMSE and PSNR come from bench_image_error (tools/bench_image_error.c says how).
# Environment: PT (default build/pt), ERR (default build/tools/bench_image_error), SIZE (128),
# SPPS ("4 16 64 128"), REF_SPP (4096), DEVICE (pt's --device; default pt's), TIMING_DEVICES
# ("cpu", add gpu on an NVIDIA machine). From a bundle: PT=bin/pt ERR=bin/bench_image_error.
set -eu
PT=${PT:-build/pt}
ERR=${ERR:-build/tools/bench_image_error}
SIZE=${SIZE:-128}
SPPS=${SPPS:-4 16 64 128}
REF_SPP=${REF_SPP:-4096}
TIMING_DEVICES=${TIMING_DEVICES:-cpu}
out=${1:-out/bench-denoise}
root=$(cd "$(dirname "$0")/.." && pwd)
[ -d "$root/scenes" ] || root=$(cd "$(dirname "$PT")/.." && pwd) # a bundle: bin/ beside scenes/
mkdir -p "$out/envtex"
dev=${DEVICE:+--device $DEVICE}
color_only=0 # 1: the next render's denoiser gets no guides (PT_DENOISE_COLOR_ONLY)

cp "$root/scenes/venice/sphere.obj" "$root/scenes/venice/sphere.mtl" \
   "$root/scenes/venice/venice_sunset_1k.hdr" "$out/envtex/"
cat > "$out/envtex/scene.json" <<'JSON'
{
  "camera": {"eye": [0, 0.6, 4.5], "target": [0, -0.2, 0], "up": [0, 1, 0], "fov_y": 40},
  "render": {"max_depth": 6},
  "textures": {
    "marble": {"type": "noise", "color0": [0.9, 0.85, 0.8], "color1": [0.15, 0.2, 0.35],
               "frequency": 6.0, "octaves": 5, "seed": 1},
    "tiles": {"type": "noise", "color0": [0.6, 0.55, 0.5], "color1": [0.1, 0.08, 0.06],
              "frequency": 12.0, "octaves": 3, "seed": 2}},
  "materials": {"ball": {"type": "diffuse", "albedo": "marble"},
                "floor": {"type": "diffuse", "albedo": "tiles"}},
  "objects": [{"obj": "sphere.obj"}],
  "environment": {"file": "venice_sunset_1k.hdr", "scale": 1.0, "rotation": 0}
}
JSON
cornell=$root/scenes/cornell-box/scene.json
lens='{"eye": [0, 1, 3.9], "target": [0, 1, 0], "up": [0, 1, 0], "fov_y": 39.3, "aperture": 0.25, "focus_distance": 4.9}'

# render NAME SPP SEED [pt options...]: OUT/NAME.exr
render() {
    name=$1; spp=$2; seed=$3; shift 3
    case $name in
        cornell*) file=$cornell ;;
        dof*) file=$cornell; set -- "$@" --camera "$lens" ;;
        envtex*) file=$out/envtex/scene.json ;;
    esac
    # shellcheck disable=SC2086
    env PT_DENOISE_COLOR_ONLY="$color_only" "$PT" render "$file" $dev --width "$SIZE" --height "$SIZE" --spp "$spp" --seed "$seed" \
        --quiet -o "$out/$name.exr" "$@" >/dev/null
}

csv=$out/denoise.csv
echo "scene,spp,mode,relmse,psnr" | tee "$csv"
for scene in cornell envtex dof; do
    render "$scene-ref" "$REF_SPP" 7
    for spp in $SPPS; do
        render "$scene-$spp-noisy" "$spp" 1
        render "$scene-$spp-denoised" "$spp" 1 --denoise
        color_only=1
        render "$scene-$spp-color-only" "$spp" 1 --denoise
        color_only=0
        for mode in noisy denoised color-only; do
            echo "$scene,$spp,$mode,$("$ERR" "$out/$scene-$spp-$mode.exr" "$out/$scene-ref.exr")" |
                tee -a "$csv"
        done
    done
done

# Denoising time at 1920x1080 (the Cornell box, 16 spp), from pt's own report lines.
for d in $TIMING_DEVICES; do
    # shellcheck disable=SC2086
    log=$("$PT" render "$cornell" $dev --width 1920 --height 1080 --spp 16 --denoise \
          --denoise-device "$d" -o "$out/timing-$d.exr" 2>&1 >/dev/null)
    seconds=$(echo "$log" | sed -n 's/^pt: denoised with .* in \([0-9.]*\) s$/\1/p')
    guide=$(echo "$log" | sed -n 's/^pt: AOV pass: \([0-9]*\) spp in \([0-9.]*\) s$/\2,\1/p')
    echo "$log" | grep -E 'warning|denoised with' >&2 || true
    echo "timing,1920x1080,$d,${seconds:-failed},${guide:-?}" | tee -a "$csv"
done
