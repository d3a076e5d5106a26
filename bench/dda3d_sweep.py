#!/usr/bin/env python3
"""Error against run time of the implicit 3D DDA over the time step and the normal penalty
(kt = kn / 10), on the two closed forms of seed 001's checks. Prints Markdown tables.

  wedge:   `rockcontact safety-factor` on examples/scenes3d/wedge.json against Hoek & Bray's
           2.198193 (the library's wedge_limit_equilibrium on the same joints).
  incline: `rockcontact run` of a unit cube on a slab under gravity tilted by 30 degrees
           (phi = 20 degrees), its slide after 1 s against 1/2 g (sin t - cos t tan phi) t^2.

    python3 bench/dda3d_sweep.py build/rockcontact
"""
import csv
import json
import math
import pathlib
import subprocess
import sys
import tempfile
import time

WEDGE_FS = 2.198193
SWEEP = [(kn, dt) for kn in (1e9, 1e10, 1e11) for dt in (2e-3, 1e-3, 5e-4)]
CUBE_FACES = [[0, 3, 2, 1], [4, 5, 6, 7], [0, 1, 5, 4], [1, 2, 6, 5], [2, 3, 7, 6], [3, 0, 4, 7]]


def box(lo, hi):
    (x0, y0, z0), (x1, y1, z1) = lo, hi
    return [[x0, y0, z0], [x1, y0, z0], [x1, y1, z0], [x0, y1, z0],
            [x0, y0, z1], [x1, y0, z1], [x1, y1, z1], [x0, y1, z1]]


def timed(command):
    start = time.monotonic()
    out = subprocess.run(command, capture_output=True, text=True, check=True)
    return out, time.monotonic() - start


def wedge(exe, tmp):
    scene = json.loads((pathlib.Path(__file__).parent.parent / "examples/scenes3d/wedge.json").read_text())
    print("| dt (s) | kn (N/m) | factor of safety | error | trials | wall s |")
    print("|---|---|---|---|---|---|")
    for kn, dt in SWEEP:
        scene["time"]["dt"] = dt
        scene["contact"]["kn"], scene["contact"]["kt"] = kn, kn / 10
        path = tmp / "wedge.json"
        path.write_text(json.dumps(scene))
        out, wall = timed([exe, "safety-factor", str(path), "--block", "wedge", "-o", "-"])
        result = json.loads(out.stdout)
        fs = result["factor_of_safety"]
        print(f"| {dt:g} | {kn:g} | {fs:.4f} | {(fs - WEDGE_FS) / WEDGE_FS:+.2%} | {result['iterations']} | {wall:.1f} |")


def incline(exe, tmp):
    g, theta, phi = 9.81, math.radians(30), math.radians(20)
    print("| dt (s) | kn (N/m) | slide (m) | error | steps | wall s |")
    print("|---|---|---|---|---|---|")
    for kn, dt in SWEEP:
        scene = {"dimension": 3, "time": {"dt": dt, "duration": 1.0},
                 "gravity": [g * math.sin(theta), 0, -g * math.cos(theta)],
                 "materials": {"rock": {"density": 2500, "youngs_modulus": 1e10, "poisson_ratio": 0.25}},
                 "contact": {"law": "penalty", "kn": kn, "kt": kn / 10, "friction_angle_deg": 20},
                 "blocks": [{"id": "slab", "material": "rock", "fixed": True,
                             "vertices": box([-2, -2, -1], [6, 2, 0]), "faces": CUBE_FACES},
                            {"id": "cube", "material": "rock", "rigid": True,
                             "vertices": box([-0.5, -0.5, 0], [0.5, 0.5, 1]), "faces": CUBE_FACES}],
                 "output": {"track": ["cube"], "every": 1000000}}
        path = tmp / "incline.json"
        path.write_text(json.dumps(scene))
        out, wall = timed([exe, "run", str(path), "--out", str(tmp / "incline")])
        rows = list(csv.DictReader(open(tmp / "incline" / "tracks.csv")))
        t = float(rows[-1]["t"])
        slide = float(rows[-1]["x"]) - float(rows[0]["x"])
        expected = 0.5 * g * (math.sin(theta) - math.cos(theta) * math.tan(phi)) * t * t
        steps = json.loads((tmp / "incline" / "summary.json").read_text())["steps"]
        print(f"| {dt:g} | {kn:g} | {slide:.6f} | {(slide - expected) / expected:+.3%} | {steps} | {wall:.2f} |")


def main() -> None:
    exe = sys.argv[1] if len(sys.argv) > 1 else "build/rockcontact"
    with tempfile.TemporaryDirectory() as name:
        tmp = pathlib.Path(name)
        print("Wedge (seed 001 §6.1), factor of safety against 2.198193:\n")
        wedge(exe, tmp)
        print("\nIncline 30°, φ = 20°, slide after 1 s against ½ g (sin θ − cos θ tan φ) t²:\n")
        incline(exe, tmp)


if __name__ == "__main__":
    main()
