#!/usr/bin/env python3
"""Error against run time of the §6.1 wedge's factor of safety (seed 001) over the time step
and the normal penalty: `rockcontact safety-factor` on copies of examples/scenes3d/wedge.json
with dt and kn (kt = kn / 10) changed, against Hoek & Bray's 2.198 (the library's
wedge_limit_equilibrium on the same joints). Prints a Markdown table.

    python3 bench/wedge3d_sweep.py build/rockcontact
"""
import json
import pathlib
import subprocess
import sys
import tempfile
import time

REFERENCE = 2.198193  # wedge_limit_equilibrium on joints 50/110 and 55/240, phi = 40 degrees


def main() -> None:
    exe = sys.argv[1] if len(sys.argv) > 1 else "build/rockcontact"
    scene = json.loads((pathlib.Path(__file__).parent.parent / "examples/scenes3d/wedge.json").read_text())
    print("| dt (s) | kn (N/m) | factor of safety | error | trials | wall s |")
    print("|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as tmp:
        for kn in (1e9, 1e10, 1e11):
            for dt in (2e-3, 1e-3, 5e-4):
                scene["time"]["dt"] = dt
                scene["contact"]["kn"] = kn
                scene["contact"]["kt"] = kn / 10
                path = pathlib.Path(tmp) / "wedge.json"
                path.write_text(json.dumps(scene))
                start = time.monotonic()
                out = subprocess.run([exe, "safety-factor", str(path), "--block", "wedge", "-o", "-"],
                                     capture_output=True, text=True, check=True)
                wall = time.monotonic() - start
                result = json.loads(out.stdout)
                fs = result["factor_of_safety"]
                print(f"| {dt:g} | {kn:g} | {fs:.4f} | {(fs - REFERENCE) / REFERENCE:+.2%} | "
                      f"{result['iterations']} | {wall:.1f} |")


if __name__ == "__main__":
    main()
