#!/bin/sh
# hotmesh sample forward_step: the FEM run and the mesh motions, as a user runs them.
# CalculiX solves the metal under the lower wall (metal.inp -> metal.frd); hotmesh lists what
# the results hold, then moves the CFD mesh with one sliding wall over the step's foot and
# fillet (forward_step.yaml), the same wall with features off (forward_step-nofeatures.yaml) and
# the wall split at the foot (forward_step-split.yaml), and checks each moved mesh against the
# deflected CAD wall: nodes on it to rounding, faces within 0.01 mm (1e-3 of the channel height).
#
# Run from anywhere:  samples/forward_step/run.sh   (HOTMESH=path/to/hotmesh to choose the
# binary; default: build/app/hotmesh of this checkout, else hotmesh on the PATH).
set -eu
here=$(cd "$(dirname "$0")" && pwd)
cd "$here"
hotmesh=${HOTMESH:-$here/../../build/app/hotmesh}
[ -x "$hotmesh" ] || hotmesh=hotmesh

ccx -i metal > metal.log                     # FEM: the heated metal, a fraction of a second
"$hotmesh" fem metal.frd --inp metal.inp     # what the results hold: steps, sets, |u|
for case in forward_step forward_step-nofeatures forward_step-split; do
  echo "== $case"
  "$hotmesh" deform "$case.yaml"             # into $case-out/
  "$hotmesh" check "$case-out/deformed.msh" --case "$case.yaml" --wall-tol 0.01
done
