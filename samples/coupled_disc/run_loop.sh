#!/bin/sh
# hotmesh sample coupled_disc: two iterations of the coupled FEA/CFD loop on the stator well.
# Each iteration: CalculiX solves the rotor (disc_<i>.inp -> disc_<i>.frd), hotmesh reads
# its displacements straight from the .frd and moves the CFD sector (case_<i>.yaml); the
# second iteration restarts from the first one's state (case_1-out/restart.hmr, eq. 22).
# In a real loop the CFD solver runs on case_<i>-out/deformed.msh between the two and gives
# the metal temperatures of the next deck; here disc_2.inp is simply 40 degrees hotter.
#
# Run from anywhere:  samples/coupled_disc/run_loop.sh   (HOTMESH=path/to/hotmesh to choose
# the binary; default: build/app/hotmesh of this checkout, else hotmesh on the PATH).
set -eu
here=$(cd "$(dirname "$0")" && pwd)
cd "$here"
hotmesh=${HOTMESH:-$here/../../build/app/hotmesh}
[ -x "$hotmesh" ] || hotmesh=hotmesh

for i in 1 2; do
  echo "== coupling iteration $i"
  ccx -i "disc_$i" > "disc_$i.log"                   # FEM: the rotor at this iteration's load
  "$hotmesh" fem "disc_$i.frd" --inp "disc_$i.inp"   # what the results hold: steps, sets, |u|
  "$hotmesh" deform "case_$i.yaml"                   # mesh motion: walls from disc_$i.frd
  "$hotmesh" check "case_$i-out/deformed.msh" --case "case_$i.yaml"   # walls on the deflected CAD
  # ... the CFD solver would run here on case_$i-out/deformed.msh ...
done
