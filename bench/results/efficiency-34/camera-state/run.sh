#!/bin/bash
# Session 6, call C: error per second against Mitsuba with the kept binary (implied camera state).
set -u
O=$OUT
T0=$(date +%s); el() { echo $(( $(date +%s) - T0 )); }
mkdir -p /tmp/icd && echo libnvidia-opencl.so.1 > /tmp/icd/nvidia.icd && cp /etc/OpenCL/vendors/*.icd /tmp/icd/ 2>/dev/null
export OCL_ICD_VENDORS=/tmp/icd
mkdir -p /tmp/ptlib && tar xJf .gpu44/libs-small.tar.xz -C /tmp/ptlib
export LD_LIBRARY_PATH=/tmp/ptlib/lib XDG_CACHE_HOME=/tmp/ptcache
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | tee $O/gpu.txt
python3 -m pip install -q --no-index --no-deps --no-compile --no-cache-dir --target /tmp/site .whl/*.whl > $O/pip.txt 2>&1 && export PYTHONPATH=/tmp/site
echo "== setup $(el) s"
B="--device gpu --variant cuda_ad_rgb --width 1280 --height 960 --spp 64 --seeds 2 --ref-spp 4096 --cache /tmp/effref"
# Run twice: as below, then with --scenes cornell,env-gold,caustics,rough-metals (the references cached on the machine).
timeout $(( 200 - $(el) )) python3 tools/bench_efficiency.py --pt .gpu44/pt-new $B --scenes small-light,torus-100k --samplers pt:sobol,mitsuba:independent,mitsuba:stratified,mitsuba:multijitter,mitsuba:ldsampler --csv $O/eff.csv > $O/eff.txt 2>&1
echo "eff rc=$?"; tail -12 $O/eff.txt
echo "== done $(el) s"
