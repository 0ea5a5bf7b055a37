# hotmesh python: the `hotmesh` module against the command (HOTMESH_EXE, set by ctest) on the
# 2D ramp sample: the mesh moved from NumPy arrays, a second coupling iteration in memory
# against the command's restart, the arrays refused, the check.
import os
import shutil
import subprocess
import threading
import time
from pathlib import Path

import numpy as np
import pytest

import hotmesh

SOURCE = Path(os.environ.get("HOTMESH_SOURCE_DIR", Path(__file__).resolve().parents[2]))
RAMP = SOURCE / "samples" / "ramp2d"
CASE = RAMP / "ramp2d-sliding.yaml"
HOTMESH = os.environ.get("HOTMESH_EXE", str(SOURCE / "build" / "app" / "hotmesh"))
# The second coupling iteration: the ramp's deflection scaled by this.
SECOND = 0.7


def ramp_table(scale=1.0):
    t = np.loadtxt(RAMP / "ramp.csv", delimiter=",", comments="#", skiprows=3)
    return t[:, :2], scale * t[:, 2:4]


def msh_points(path):
    """The node coordinates of a gmsh 4.1 text file, in the file's order of node tags."""
    lines = Path(path).read_text().splitlines()
    at = lines.index("$Nodes") + 1
    blocks, nodes = (int(v) for v in lines[at].split()[:2])
    at += 1
    tags, points = [], []
    for _ in range(blocks):
        count = int(lines[at].split()[3])
        tags += [int(v) for v in lines[at + 1:at + 1 + count]]
        points += [[float(v) for v in row.split()] for row in lines[at + 1 + count:at + 1 + 2 * count]]
        at += 1 + 2 * count
    assert len(points) == nodes
    order = np.argsort(tags)
    return np.array(tags)[order], np.array(points)[order]


def run_command(case, output):
    subprocess.run([HOTMESH, "deform", str(case), "-o", str(output), "-q"], check=True)


def second_case(folder, restart):
    """The sliding ramp's case with the second iteration's table, restarted from `restart`."""
    nodes, displacements = ramp_table(SECOND)
    table = folder / "ramp-second.csv"
    np.savetxt(table, np.hstack([nodes, displacements]), delimiter=",", header="x,y,dx,dy", comments="",
               fmt="%.17g")
    case = folder / "second.yaml"
    case.write_text(f"mesh: {RAMP / 'ramp2d.msh'}\nsolver: {{increments: 16, newton_tolerance: 1.0e-4}}\n"
                    f"restart: {restart}\npatches:\n  left: {{role: fixed}}\n  right: {{role: slip}}\n"
                    f"  top: {{role: sliding}}\n  bottom: {{role: sliding, deflection: {{file: {table}, degree: 1}}}}\n")
    return case


@pytest.fixture(scope="module")
def command_runs(tmp_path_factory):
    """The command's two coupling iterations: the sample, then the second table restarted."""
    folder = tmp_path_factory.mktemp("command")
    run_command(CASE, folder / "first")
    run_command(second_case(folder, folder / "first" / "restart.hmr"), folder / "second")
    return folder


@pytest.fixture(scope="module")
def first_result():
    case = hotmesh.Case(CASE)
    nodes, displacements = ramp_table()
    case.set_deflection("bottom", nodes=nodes, displacements=displacements)
    return case, case.deform()


def test_ramp_moved_from_arrays_is_the_commands_mesh(command_runs, first_result, tmp_path):
    _, result = first_result
    assert result.success and result.dimension == 2
    tags, expected = msh_points(command_runs / "first" / "deformed.msh")
    assert result.points.shape == (len(tags), 2) and result.points.dtype == np.float64
    assert np.array_equal(result.node_ids, tags)
    assert np.max(np.abs(result.points - expected[:, :2])) <= 1e-12
    # No copy: a read-only view of the result's own memory.
    assert result.points.base is not None and not result.points.flags.writeable
    assert 0.0 < result.min_scaled_jacobian == pytest.approx(np.min(result.scaled_jacobians))
    report = result.report
    assert report["status"] == "success" and report["command"] == "deform"
    assert report["min_scaled_jacobian"] == pytest.approx(result.min_scaled_jacobian)
    assert result.quality["max_skewness"] == pytest.approx(report["quality"]["skewness"]["max"])
    # The files the command writes: the same mesh, byte for byte.
    result.write(tmp_path / "out")
    for name in ("deformed.msh", "deformed.vtu", "report.json", "restart.hmr", "deformed.png"):
        assert (tmp_path / "out" / name).is_file(), name
    assert (tmp_path / "out" / "deformed.msh").read_bytes() == (command_runs / "first" / "deformed.msh").read_bytes()
    assert hotmesh.check(tmp_path / "out" / "deformed.msh", case=CASE).passed


def test_second_iteration_in_memory_is_the_commands_restart(command_runs, first_result):
    case, first = first_result
    nodes, displacements = ramp_table(SECOND)
    case.set_deflection("bottom", nodes=nodes, displacements=displacements)
    second = case.deform(first)
    assert second.success
    _, expected = msh_points(command_runs / "second" / "deformed.msh")
    assert np.max(np.abs(second.points - expected[:, :2])) <= 1e-12
    # It is not the first iteration's mesh: the walls moved back.
    assert np.max(np.abs(second.points - first.points)) > 1e-3


def test_the_example_of_the_issue_runs_as_written(tmp_path):
    case = hotmesh.Case(str(CASE))
    t = np.loadtxt(RAMP / "ramp.csv", delimiter=",", comments="#", skiprows=3)
    case.set_deflection("bottom", nodes=t[:, :2], displacements=t[:, 2:4])
    seen = []
    result = case.deform(progress=seen.append)
    assert result.points.shape[1] == 2 and result.min_scaled_jacobian > 0
    result.write(tmp_path / "out")
    assert hotmesh.check(str(tmp_path / "out" / "deformed.msh"), case=str(CASE)).passed
    # Every increment, then the sliding walls' corner passes; Newton steps in between.
    done = [p for p in seen if p.newton_iteration == 0 and p.accepted]
    assert [p.increment for p in done if not p.corner_pass] == list(range(1, 17))
    assert all(p.increment > 16 for p in done if p.corner_pass) and any(p.corner_pass for p in done)
    assert all(p.increments == 16 for p in seen)
    assert all(p.residual_reduction <= 1e-4 for p in done if not p.corner_pass)
    assert all(p.min_scaled_jacobian > 0.4 for p in done)
    assert sum(p.newton_iteration > 0 for p in seen) >= 16


class Stop(Exception):
    pass


def test_a_progress_callback_that_raises_stops_the_motion_and_the_case_moves_again(first_result):
    case = hotmesh.Case(CASE)
    steps = []

    def stop_after_three(p):
        steps.append(p)
        if len(steps) == 3:
            raise Stop("enough")

    with pytest.raises(Stop, match="enough"):
        case.deform(progress=stop_after_three)
    assert len(steps) == 3
    with pytest.raises(hotmesh.InputError, match="progress must be a callable"):
        case.deform(progress=3)
    assert np.array_equal(case.deform().points, first_result[1].points)


def test_the_motion_lets_other_python_threads_run():
    case = hotmesh.Case(CASE)
    ticks = []
    running = threading.Event()
    running.set()

    def tick():
        while running.is_set():
            ticks.append(1)
            time.sleep(0.002)

    ticker = threading.Thread(target=tick)
    ticker.start()
    try:
        before = len(ticks)
        started = time.monotonic()
        case.deform()
        seconds = time.monotonic() - started
        during = len(ticks) - before
    finally:
        running.clear()
        ticker.join()
    # Holding the GIL, the motion would leave the ticker a tick or two.
    assert seconds > 0.2 and during >= 10 * seconds


@pytest.mark.parametrize(
    "nodes, displacements, words",
    [
        (np.zeros(8), np.zeros(8), ["nodes", "shape (8,)"]),
        (np.zeros((4, 4)), np.zeros((4, 4)), ["nodes", "shape (4, 4)"]),
        (np.zeros((4, 2)), np.zeros((3, 2)), ["shape (4, 2)", "displacements (3, 2)"]),
        (np.zeros((4, 2), dtype=complex), np.zeros((4, 2)), ["nodes", "dtype complex128"]),
        ([["a", "b"]], [[0.0, 0.0]], ["nodes", "dtype <U1"]),
        (np.array([[0.0, 0.0], [1.0, np.nan]]), np.zeros((2, 2)), ["nodes[1, 1] is nan"]),
        (np.zeros((2, 2)), np.array([[0.0, np.inf], [0.0, 0.0]]), ["displacements[0, 1] is inf"]),
    ],
)
def test_bad_arrays_are_refused_naming_the_argument(nodes, displacements, words):
    case = hotmesh.Case(CASE)
    with pytest.raises(hotmesh.InputError) as error:
        case.set_deflection("bottom", nodes=nodes, displacements=displacements)
    assert isinstance(error.value, ValueError)
    for word in words:
        assert word in str(error.value)
    assert "set_deflection(bottom)" in str(error.value)


def test_input_errors_name_the_file_key_or_patch(tmp_path):
    with pytest.raises(ValueError, match="no-such-case.yaml"):
        hotmesh.Case(tmp_path / "no-such-case.yaml")
    bad = tmp_path / "bad.yaml"
    bad.write_text(f"mesh: {RAMP / 'ramp2d.msh'}\nsolver: {{increments: 0}}\npatches:\n  left: {{role: fixed}}\n")
    with pytest.raises(hotmesh.InputError, match=r"bad.yaml:2: solver.increments"):
        hotmesh.Case(bad)
    case = hotmesh.Case(CASE)
    nodes, displacements = ramp_table()
    with pytest.raises(hotmesh.InputError, match="no patch 'floor'.*left, right, top, bottom"):
        case.set_deflection("floor", nodes=nodes, displacements=displacements)
    with pytest.raises(hotmesh.InputError, match="patch 'left' is fixed"):
        case.set_deflection("left", nodes=nodes, displacements=displacements)


def test_check_fails_a_mesh_off_the_cases_walls(command_runs):
    checked = hotmesh.check(command_runs / "first" / "deformed.msh", case=CASE)
    assert checked.passed and {p.patch for p in checked.patches} == {"top", "bottom"}
    # The second iteration's mesh follows the smaller ramp: the first case's walls are not its.
    moved_back = hotmesh.check(command_runs / "second" / "deformed.msh", case=CASE)
    assert not moved_back.passed
    bottom = next(p for p in moved_back.patches if p.patch == "bottom")
    assert not bottom.passed and bottom.max_distance > 100 * moved_back.tolerance
    assert moved_back.report["patches"][0]["patch"] in ("top", "bottom")
    # A mesh the case was not deformed into.
    other = SOURCE / "samples" / "duct3d" / "duct-hybrid-mixed.msh"
    with pytest.raises(hotmesh.InputError, match="duct-hybrid-mixed.msh: .* nodes in 3D, but the case's mesh"):
        hotmesh.check(other, case=CASE)


def test_a_case_built_in_code_moves_as_its_case_file(first_result, tmp_path):
    shutil.copy(RAMP / "ramp2d.msh", tmp_path / "ramp2d.msh")
    case = hotmesh.Case.from_mesh(tmp_path / "ramp2d.msh", [("left", "fixed"), ("right", "slip"), ("top", "sliding"),
                                                            ("bottom", "sliding")])
    assert case.patches == ["left", "right", "top", "bottom"] and case.role("right") == "slip"
    nodes, displacements = ramp_table()
    case.set_deflection("bottom", nodes=nodes, displacements=displacements)
    result = case.deform()
    assert np.array_equal(result.points, first_result[1].points)
    assert hotmesh.version() == hotmesh.__version__
