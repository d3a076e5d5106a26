#!/usr/bin/env python3
"""The 2D initial equilibrium against the number of blocks (docs/performance.md).

Writes a joint-cut mass of 1 m blocks on a fixed floor for each size given (a region w x h cut
by joints at 0 and 90 degrees; rho 2700, E 2 GPa, nu 0.25, kn 2 GPa, kt 1 GN/m, phi 30 deg,
H 1 m, dt 2e-4 s, 0.01 s of steps after the start, the default "initial_equilibrium": "auto"),
runs `rockcontact run` on it, and prints a row of the performance table per mass: the
pre-solve's iterations, ratio reached, whether it converged, how many blocks it named, its
seconds (summary.json), the run's wall seconds and peak memory (the child's rusage).

    python3 bench/presolve2d.py [--rockcontact build/rockcontact] 32x32 150x30 333x30
"""

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time


def scene(w, h):
    return {
        "dimension": 2,
        "time": {"dt": 2e-4, "duration": 0.01},
        "gravity": [0, -9.81],
        "materials": {"rock": {"density": 2700, "youngs_modulus": 2e9, "poisson_ratio": 0.25}},
        "contact": {"law": "potential", "kn": 2e9, "kt": 1e9, "friction_angle_deg": 30, "H": 1.0},
        "region": {"vertices": [[0, 0], [w, 0], [w, h], [0, h]], "material": "rock", "group": "rock",
                   "id_prefix": "b"},
        "joint_sets": [{"dip_deg": 0, "spacing": 1, "offset": 0}, {"dip_deg": 90, "spacing": 1, "offset": 0}],
        "boundaries": [{"id": "floor", "material": "rock", "group": "boundary", "from": [-1, 0],
                        "to": [w + 1, 0], "depth": 1}],
        "output": {"every": 1000},
    }


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--rockcontact", default="build/rockcontact")
    parser.add_argument("sizes", nargs="+", help="w x h, e.g. 333x30")
    args = parser.parse_args()
    print("| blocks (w × h) | iterations | ratio reached | converged | unsettled | pre-solve s | run s | peak MB |")
    print("|---|--:|--:|---|--:|--:|--:|--:|")
    with tempfile.TemporaryDirectory() as work:
        for size in args.sizes:
            w, h = (int(v) for v in size.lower().split("x"))
            path = os.path.join(work, f"grid{w}x{h}.json")
            with open(path, "w") as f:
                json.dump(scene(w, h), f)
            out = os.path.join(work, f"out{w}x{h}")
            env = dict(os.environ, OMP_WAIT_POLICY="passive")
            with open(os.path.join(work, "stderr.txt"), "w+") as err:
                started = time.monotonic()
                child = subprocess.Popen([args.rockcontact, "run", path, "--out", out], env=env,
                                         stdout=subprocess.DEVNULL, stderr=err)
                _, status, usage = os.wait4(child.pid, 0)
                wall = time.monotonic() - started
                child.returncode = os.waitstatus_to_exitcode(status)
                if child.returncode != 0:
                    err.seek(0)
                    sys.exit(f"{size}: rockcontact run failed ({child.returncode}): {err.read().strip()}")
            peak_mb = usage.ru_maxrss / 1024
            with open(os.path.join(out, "summary.json")) as f:
                e = json.load(f)["initial_equilibrium"]
            print(f"| {w} × {h} ({w * h}) | {e['iterations']} | {e['ratio']:.2g} | "
                  f"{'yes' if e['converged'] else 'no'} | {len(e['unsettled'])} | {e['seconds']:.3g} | "
                  f"{wall:.3g} | {peak_mb:.0f} |", flush=True)


if __name__ == "__main__":
    main()
