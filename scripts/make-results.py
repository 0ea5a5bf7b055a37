#!/usr/bin/python3
"""hotmesh: regenerates the results pages of the samples (docs/results/*.md).

Runs each sample case with the built hotmesh (after the sample's FEM run, where it has one),
measures the walls with wall_metrics (or, for walls on CAD deflected by FEM results, with
`hotmesh check --case`), copies the pictures to docs/results/img/ and rewrites the table between
the markers
<!-- results:<sample>:begin --> and <!-- results:<sample>:end --> of docs/results/<sample>.md.
Usage: scripts/make-results.sh (builds first), or scripts/make-results.py BUILD_DIR [SAMPLE...]
(only the samples named, e.g. step2d; all of them without).
"""
import json
import os
import platform
import re
import shutil
import subprocess
import sys
from datetime import date

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

# sample -> [(label, case file, wall patch, table, (xmin, xmax) of the region to count nodes in)];
# table None: the wall is measured by `hotmesh check --case` against the deflected CAD wall.
SAMPLES = {
    "ramp2d": [
        ("without sliding", "ramp2d.yaml", "bottom", "ramp.csv", (0.975, 1.025)),
        ("sliding, features off (the paper's)", "ramp2d-sliding-nofeatures.yaml", "bottom", "ramp.csv", (0.975, 1.025)),
        ("sliding with features", "ramp2d-sliding.yaml", "bottom", "ramp.csv", (0.975, 1.025)),
        ("triangles, without sliding", "ramp2d-triangles.yaml", "bottom", "ramp.csv", (0.975, 1.025)),
        ("triangles, sliding with features", "ramp2d-triangles-sliding.yaml", "bottom", "ramp.csv", (0.975, 1.025)),
        ("quads on the wall, triangles above, without sliding", "ramp2d-hybrid.yaml", "bottom", "ramp.csv", (0.975, 1.025)),
        ("quads on the wall, triangles above, sliding with features", "ramp2d-hybrid-sliding.yaml", "bottom", "ramp.csv",
         (0.975, 1.025)),
    ],
    "shear2d": [
        ("without sliding", "shear2d.yaml", "top", "top.csv", None),
        ("with sliding", "shear2d-sliding.yaml", "top", "top.csv", None),
    ],
    "step2d": [
        ("without sliding", "step2d.yaml", "bottom", "bump.csv", (1.2, 1.8)),
        ("sliding, features off (the paper's)", "step2d-sliding-nofeatures.yaml", "bottom", "bump.csv", (1.2, 1.8)),
        ("sliding with features", "step2d-sliding.yaml", "bottom", "bump.csv", (1.2, 1.8)),
    ],
    "forward_step": [
        ("one sliding wall", "forward_step.yaml", "wall", None, None),
        ("one sliding wall, features off", "forward_step-nofeatures.yaml", "wall", None, None),
        ("the wall split at the foot", "forward_step-split.yaml", "floor,step", None, None),
    ],
}

# sample -> the FEM run its cases read, run in the sample's folder first.
FEM_RUNS = {"forward_step": ["ccx", "-i", "metal"]}

# The run the time column compares with, when it is not the sample's run without sliding.
BASELINES = {"forward_step": "the single sliding wall"}

# sample -> the runs whose pictures its page shows, where not every run's: the others move the
# mesh the same.
PICTURES = {"forward_step": ["forward_step.yaml"]}

# What the region (xmin, xmax) of a sample is, for the column of wall nodes in it.
REGION_NAMES = {"ramp2d": "ramp", "step2d": "bump"}

def machine():
    model = "unknown CPU"
    try:
        for line in subprocess.run(["lscpu"], capture_output=True, text=True).stdout.splitlines():
            if line.startswith("Model name:"):
                model = line.split(":", 1)[1].strip()
    except OSError:
        pass
    load = os.getloadavg()[0]
    return f"{model}, {os.cpu_count()} cores, {platform.system()} {platform.release()}; load average {load:.2f} at the start"


def run_case(build, sample, label, case, wall, table, region, out_root):
    sample_dir = os.path.join(ROOT, "samples", sample)
    stem = os.path.splitext(case)[0]
    out = os.path.join(out_root, stem)
    env = dict(os.environ, OMP_WAIT_POLICY="PASSIVE")
    command = [os.path.join(build, "app", "hotmesh"), "-q", "deform", os.path.join(sample_dir, case), "-o", out]
    subprocess.run(command, check=True, env=env)
    report = json.load(open(os.path.join(out, "report.json")))
    if table is None:
        metrics = check_metrics(build, os.path.join(out, "deformed.msh"), os.path.join(sample_dir, case))
    else:
        args = [os.path.join(build, "samples", "tools", "wall_metrics"), os.path.join(out, "deformed.msh"), wall,
                os.path.join(sample_dir, table)]
        if region:
            args += [str(region[0]), str(region[1])]
        metrics = json.loads(subprocess.run(args, check=True, capture_output=True, text=True).stdout)
    img = os.path.join(ROOT, "docs", "results", "img")
    os.makedirs(img, exist_ok=True)
    pictures = []
    shown = case in PICTURES.get(sample, [case])
    for name in sorted(os.listdir(out)):
        if shown and name.endswith(".png"):
            target = f"{stem}-{name}"
            shutil.copyfile(os.path.join(out, name), os.path.join(img, target))
            pictures.append(target)
    return {"label": label, "case": case, "report": report, "metrics": metrics, "pictures": pictures}


def check_metrics(build, mesh, case):
    """The largest two-sided distance of the walls' faces from the deflected walls, as
    hotmesh check --case measures it, in wall_metrics' key."""
    command = [os.path.join(build, "app", "hotmesh"), "-q", "check", mesh, "--case", case, "--format", "json"]
    report = json.loads(subprocess.run(command, check=True, capture_output=True, text=True).stdout)
    return {"max_distance_to_exact_wall": max(p["wall"]["hausdorff"] for p in report["patches"])}


def corners(report):
    """The corners report.json lists: how many, and by what they were held."""
    held = [f.get("held", "") for f in report.get("features", [])]
    kinds = sorted(set(held))
    return f"{len(held)}" + (f" ({', '.join(k.replace('_', ' ') for k in kinds)})" if held else "")


def table(sample, runs):
    base = runs[0]["report"]["seconds"]["motion"]
    has_region = SAMPLES[sample][0][4] is not None
    on_cad = SAMPLES[sample][0][3] is None
    lines = [
        "| run | min scaled Jacobian | inverted cells | " +
        (f"wall nodes on the {REGION_NAMES[sample]} | " if has_region else "") +
        ("max distance wall–deflected wall | corners held | " if on_cad else "max distance wall–exact | ") +
        "sliding nodes | increments (attempts) | Newton iterations | PCG iterations | "
        f"time of the motion (s) | ratio to {BASELINES.get(sample, 'without sliding')} |",
        "|---|---|---|" + ("---|" if has_region else "") + ("---|" if on_cad else "") + "---|---|---|---|---|---|---|",
    ]
    for run in runs:
        r, m = run["report"], run["metrics"]
        seconds = r["seconds"]["motion"]
        lines.append(
            f"| {run['label']} (`{run['case']}`) | {r['min_scaled_jacobian']:.3f} | {r['inverted_cells']} | " +
            (f"{m['nodes_between']} | " if has_region else "") +
            f"{m['max_distance_to_exact_wall']:.4f} | " + (f"{corners(r)} | " if on_cad else "") +
            f"{r['sliding_nodes']} | {r['solver']['increments']} "
            f"({len(r['increments'])}) | {r['newton_iterations']} | {r['pcg_iterations']} | {seconds:.2f} | "
            f"{seconds / base:.1f} |")
    return "\n".join(lines)


def main():
    build = sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "build")
    out_root = os.path.join(build, "results")
    header = f"Measured on {date.today().isoformat()}: {machine()}."
    chosen = sys.argv[2:] or list(SAMPLES)
    for sample in chosen:
        if sample not in SAMPLES:
            sys.exit(f"no sample {sample}; samples: {', '.join(SAMPLES)}")
    for sample, cases in SAMPLES.items():
        if sample not in chosen:
            continue
        if sample in FEM_RUNS:
            subprocess.run(FEM_RUNS[sample], check=True, cwd=os.path.join(ROOT, "samples", sample),
                           stdout=subprocess.DEVNULL)
        runs = [run_case(build, sample, *c, os.path.join(out_root, sample)) for c in cases]
        page = os.path.join(ROOT, "docs", "results", f"{sample}.md")
        text = open(page).read()
        block = f"<!-- results:{sample}:begin -->\n{header}\n\n{table(sample, runs)}\n<!-- results:{sample}:end -->"
        text, n = re.subn(rf"<!-- results:{sample}:begin -->.*?<!-- results:{sample}:end -->", block, text, flags=re.S)
        if n != 1:
            sys.exit(f"{page}: no results markers for {sample}")
        open(page, "w").write(text)
        print(f"updated {page}")


if __name__ == "__main__":
    main()
