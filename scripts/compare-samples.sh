#!/usr/bin/env bash
# hotmesh: do two builds move the samples alike? Runs every sample case (samples/*/*.yaml, the
# duct's restart after the run it restarts from) with each of two hotmesh executables, in the
# same folder so that the paths they write are the same, and compares what they wrote: the
# meshes, VTU, restart and checkpoint files byte for byte, report.json without its timings,
# memory and thread counts. For changes that move code and must change nothing (issue 47).
#
#   scripts/compare-samples.sh OLD_HOTMESH NEW_HOTMESH [WORK_FOLDER]   (default build/compare-samples)
#
# OLD_HOTMESH is typically a copy of build/app/hotmesh made before the change. The samples'
# inputs that are not committed are made first: the CalculiX results (ccx) of forward_step and
# coupled_disc, and the stator well's CGNS and OpenFOAM sector (make_stator_well from
# build/samples). About a minute a build on two cores. Exit code 1 if anything differs.
set -euo pipefail
if (($# < 2)); then
  echo "usage: scripts/compare-samples.sh OLD_HOTMESH NEW_HOTMESH [WORK_FOLDER]" >&2
  exit 2
fi
repo=$(cd "$(dirname "$0")/.." && pwd)
old=$(readlink -f "$1")
new=$(readlink -f "$2")
work=${3:-$repo/build/compare-samples}  # the build folder: git leaves it alone
mkdir -p "$work"
work=$(readlink -f "$work")
generator=$repo/build/samples/stator_well/make_stator_well
for tool in "$old" "$new" "$generator"; do
  [[ -x $tool ]] || { echo "compare-samples: $tool is not an executable (build first)" >&2; exit 2; }
done
command -v ccx >/dev/null || { echo "compare-samples: ccx (calculix-ccx) is not installed" >&2; exit 2; }

# The inputs, made once: the CGNS sector's file holds the time it was written, and the moved
# CGNS file keeps what its input holds.
rm -rf "$work/inputs"
cp -r "$repo/samples" "$work/inputs"
find "$work/inputs" -name '*-out' -type d -prune -exec rm -rf {} +
(cd "$work/inputs/forward_step" && ccx -i metal >/dev/null)
(cd "$work/inputs/coupled_disc" && ccx -i disc_1 >/dev/null && ccx -i disc_2 >/dev/null)
"$generator" --engine-formats "$work/inputs/stator_well" >/dev/null

# run_all BINARY OUT: every case of a fresh copy of the inputs, outputs kept in OUT/<sample>__<case>.
run_all() {
  local binary=$1 out=$2
  rm -rf "$work/samples" "$out"
  mkdir -p "$out"
  cp -r "$work/inputs" "$work/samples"
  local cases
  cases=$(cd "$work" && ls samples/*/*.yaml | grep -v restart; echo samples/duct3d/duct-restart.yaml)
  for y in $cases; do
    local name=${y#samples/}
    name=${name//\//__}
    name=${name%.yaml}
    if ! (cd "$work" && OMP_NUM_THREADS=2 "$binary" -q deform "$y" >"$out/$name.log" 2>&1); then
      echo "  $name: exit code $? (log: $out/$name.log)"
    fi
    cp -r "$work/${y%.yaml}-out" "$out/$name" 2>/dev/null || true
  done
}

echo "== running the samples with $old"
run_all "$old" "$work/old"
echo "== running the samples with $new"
run_all "$new" "$work/new"

echo "== comparing"
differ=0
for run in "$work"/old/*/; do
  name=$(basename "$run")
  if [[ ! -d $work/new/$name ]]; then
    echo "$name: no output from the new build"; differ=1; continue
  fi
  same=1
  while IFS= read -r file; do
    cmp -s "$run/$file" "$work/new/$name/$file" || { echo "$name: $file differs"; same=0; }
  done < <(cd "$run" && find . -type f ! -name report.json | sort)
  if [[ -f $run/report.json ]] && ! python3 - "$run/report.json" "$work/new/$name/report.json" <<'PY'
import json, sys
# What depends on the machine and the moment, not on what was computed.
VARYING = ("seconds", "time", "memory", "version", "date", "threads", "wait", "bytes", "rss")
def strip(o):
    if isinstance(o, dict):
        return {k: strip(v) for k, v in o.items() if not any(s in k for s in VARYING)}
    if isinstance(o, list):
        return [strip(x) for x in o]
    return o
sys.exit(0 if strip(json.load(open(sys.argv[1]))) == strip(json.load(open(sys.argv[2]))) else 1)
PY
  then
    echo "$name: report.json differs"; same=0
  fi
  ((same)) && echo "$name: identical" || differ=1
done
exit $differ
