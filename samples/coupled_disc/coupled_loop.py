#!/usr/bin/env python3
# hotmesh sample coupled_disc: run_loop.sh's two coupling iterations as a Python script, the
# CFD mesh moved in memory by the hotmesh module (docs/library.md). For i = 1, 2: CalculiX
# solves the rotor (disc_<i>.inp -> disc_<i>.frd); hotmesh takes every rotor wall's
# displacements straight from the .frd and moves the stator-well sector, the second iteration
# continuing from the first one's result in memory (the paper's section 4.3: no restart file
# is read); the moved mesh is written with the files `hotmesh deform` writes (case_<i>-out/:
# deformed.msh here; deformed.cgns or polyMesh/ for a case on a CGNS or OpenFOAM mesh) and
# checked against the case's deflected walls. The meshes are those of run_loop.sh, bit for bit.
#
# Copy it for your own loop: your FEM solve in solve_fem, your walls in ROTOR_WALLS, your CFD
# solve where the comment says. Run from anywhere, with the module scripts/setup.sh builds:
#     PYTHONPATH=build/python python3 samples/coupled_disc/coupled_loop.py [FOLDER]
import subprocess
import sys
from pathlib import Path

import hotmesh

# The CFD case's rotor walls and, for each, its surface in the CalculiX deck (disc_mesh.inp).
ROTOR_WALLS = {
    "rim_up": "RIM_UP",
    "disc_up_upper": "DISC_UP_UPPER",
    "joint": "JOINT",
    "disc_up_lower": "DISC_UP_LOWER",
    "disc_base": "DISC_BASE",
    "disc_down": "DISC_DOWN",
    "rim_down": "RIM_DOWN",
}


def solve_fem(folder, iteration):
    """The FEM solve of this iteration: ccx on disc_<i>.inp; its results and deck."""
    with open(folder / f"disc_{iteration}.log", "w") as log:
        subprocess.run(["ccx", "-i", f"disc_{iteration}"], cwd=folder, stdout=log, check=True)
    return folder / f"disc_{iteration}.frd", folder / f"disc_{iteration}.inp"


def main(folder):
    solve_fem(folder, 1)
    # The sector, its CAD file, the stator's tables and the rotor walls from disc_1.frd.
    case = hotmesh.Case(folder / "case_1.yaml")
    previous = None
    for iteration in (1, 2):
        if previous is not None:
            frd, inp = solve_fem(folder, iteration)
            for patch, surface in ROTOR_WALLS.items():
                case.set_calculix_deflection(patch, frd=frd, inp=inp, set=surface)
        result = case.deform(previous) if previous is not None else case.deform()
        if not result.success:
            print(f"iteration {iteration}: the motion failed: {result.message}", file=sys.stderr)
            return 1
        output = folder / f"case_{iteration}-out"
        result.write(output)
        check = hotmesh.check(output / "deformed.msh", case=folder / f"case_{iteration}.yaml")
        print(f"iteration {iteration}: {len(result.points)} nodes, min scaled Jacobian "
              f"{result.min_scaled_jacobian:.3f}; {sum(p.passed for p in check.patches)} of "
              f"{len(check.patches)} walls on their deflected walls; outputs in {output}")
        if not check.passed:
            print(check.text, file=sys.stderr)
            return 1
        # ... the CFD solver runs here on case_<i>-out/deformed.msh, giving the metal
        # temperatures of the next iteration's deck (here disc_2.inp is simply hotter) ...
        previous = result
    return 0


if __name__ == "__main__":
    sys.exit(main(Path(sys.argv[1] if len(sys.argv) > 1 else Path(__file__).resolve().parent).resolve()))
