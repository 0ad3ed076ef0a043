#!/bin/sh
# SPDX-License-Identifier: MIT
# check-layers.sh [ROOT]: refuses includes that go against the layering of shared/DESIGN.md
# ("Layout"), and OpenCL calls outside host/device/. host/ folders may include only the folders below them; cl/ sources are assembled in
# CL_SOURCES order, which must list the folders in their dependency order. Prints each offence as
# file:line and exits 1 when there is one.
set -u
root=${1:-.}
cd "$root" || exit 2

# What each host/ folder may include (itself always), transitively closed by hand.
allowed() {
    case $1 in
        base)     echo "base" ;;
        ext)      echo "" ;;
        device)   echo "base" ;;
        parallel) echo "base device" ;;
        io)       echo "base" ;;
        scene)    echo "base io" ;;
        accel)    echo "base" ;;
        render)   echo "base device parallel io scene accel" ;;
        dist)     echo "base device parallel io scene accel render" ;;
        viewer)   echo "base device parallel io scene accel render" ;;
        app)      echo "base device parallel io scene accel render dist viewer" ;;
        *)        echo "?" ;;
    esac
}

bad=0
for f in $(find host -mindepth 2 -type f \( -name '*.c' -o -name '*.h' -o -name '*.cc' \) | sort); do
    folder=$(echo "$f" | cut -d/ -f2)
    ok=$(allowed "$folder")
    if [ "$ok" = "?" ]; then
        echo "$f: host/$folder/ is not a folder of the layout"; bad=1; continue
    fi
    grep -n '^[[:space:]]*#[[:space:]]*include[[:space:]]*"' "$f" | while IFS= read -r line; do
        n=${line%%:*}
        inc=$(echo "$line" | sed 's/.*include[[:space:]]*"\([^"]*\)".*/\1/')
        case $inc in
            ../../cl/shared.h) [ "$folder" = base ] && continue
                echo "$f:$n: includes cl/shared.h directly (use base/shared_types.h)"; continue ;;
            */*) dep=${inc%%/*} ;;
            *) echo "$f:$n: #include \"$inc\" does not name its folder"; continue ;;
        esac
        [ "$dep" = "$folder" ] && continue
        case " $ok " in
            *" $dep "*) ;;
            *) echo "$f:$n: $folder/ may not include $inc ($folder/ may use: ${ok:-nothing})" ;;
        esac
    done
done >/tmp/check-layers.$$
# scene/ has two floors: scene.h (scene_load) calls the readers (scene_json, gltf_scene,
# load_objects...), which see only scene_types.h below them. Only the top floor (scene.c, and
# scene_view.c, which frames and lights a loaded Scene) and what hashes one may include scene/scene.h.
for f in $(grep -l '^[[:space:]]*#[[:space:]]*include[[:space:]]*"scene/scene.h"' host/scene/*); do
    case ${f#host/scene/} in
        scene.c|scene.h|scene_view.c|scene_hash.c|scene_hash.h) ;;
        *) echo "$f: includes scene/scene.h, the floor above the readers (use scene/scene_types.h)" ;;
    esac
done >>/tmp/check-layers.$$
for f in host/*.c host/*.h; do
    [ -e "$f" ] || continue
    [ "$f" = host/main.c ] || echo "$f: only main.c lives at the top of host/" >>/tmp/check-layers.$$
done

# OpenCL: only device/ calls the API (shared/DESIGN.md, Layout), so that every call is checked in
# one place (CL_CHECK) and the other folders go through device/'s helpers (device_fill,
# device_run, device_release_buffer, ...). Comments are left out before looking.
grep -rnE '\bcl[A-Z][A-Za-z0-9_]*[[:space:]]*\(' host --include='*.c' --include='*.h' --include='*.cc' |
    grep -v '^host/device/' | while IFS= read -r line; do
        code=$(echo "$line" | cut -d: -f3- | sed -e 's#//.*##' -e 's#/\*.*##' -e 's#^[[:space:]]*\*.*##')
        call=$(echo "$code" | grep -oE '\bcl[A-Z][A-Za-z0-9_]*[[:space:]]*\(' | head -n 1 | tr -d ' (')
        [ -n "$call" ] &&
            echo "$(echo "$line" | cut -d: -f1-2): calls $call outside host/device/ (use a device/ helper)"
    done >>/tmp/check-layers.$$

# cl/: the assembled order must follow shared.h and its parts (cl/shared/) -> core -> geometry ->
# material -> medium -> light -> lensing -> stages; parallel/ and post/ may come anywhere after core/.
rank() {
    case $1 in
        shared.h|shared) echo 0 ;; core) echo 1 ;; geometry) echo 2 ;; material) echo 3 ;;
        medium) echo 4 ;; light) echo 5 ;; lensing) echo 6 ;; stages) echo 7 ;;
        parallel|post) echo P ;; *) echo "?" ;;
    esac
}
sources=$(sed -n '/^CL_SOURCES :=/,/^$/p' Makefile | tr -d '\\' | sed 's/CL_SOURCES :=//')
last=0
for s in $sources; do
    d=${s#cl/}; d=${d%%/*}
    r=$(rank "$d")
    case $r in
        "?") echo "Makefile CL_SOURCES: $s is not in a cl/ folder of the layout" >>/tmp/check-layers.$$ ;;
        P) [ "$last" -ge 1 ] || echo "Makefile CL_SOURCES: $s comes before cl/core/" >>/tmp/check-layers.$$ ;;
        *) if [ "$r" -lt "$last" ]; then
               echo "Makefile CL_SOURCES: $s ($d/) comes after a later layer" >>/tmp/check-layers.$$
           fi
           last=$r ;;
    esac
done

if [ -s /tmp/check-layers.$$ ]; then
    cat /tmp/check-layers.$$; rm -f /tmp/check-layers.$$
    echo "check-layers: the lines above go against the layering (shared/DESIGN.md, Layout)"
    exit 1
fi
rm -f /tmp/check-layers.$$
echo "check-layers: every include follows the layering; OpenCL calls only in host/device/"
