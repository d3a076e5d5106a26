#!/usr/bin/env python3
"""Saint-Venant's impact of two equal bars (issue 21) under the CDEM contact laws, against mesh
size and time step. Prints one Markdown table per law.

  scene:   examples/scenes_cdem/bars.json: two 1 m x 0.1 m bars, nu = 0, plane stress, the
           striker at v0 = 1 m/s, 0.1 mm from the target.
  oracle:  the 1D wave solution: the contact lasts 2 L / c (c = sqrt(E / rho)), after which the
           striker is at rest and the target moves at v0; no energy is lost but the two-scale
           law's stated onset loss (summary.json's energy.end.onset_loss).
  laws:    two-scale, two-scale with "subdivide": true, penalty with kn = 1e9, 1e10, 1e11 N/m
           per node.
  sweep:   mesh.max_edge 0.05, 0.025, 0.0125 m at dt = 0.8 x the critical step, and on the
           middle mesh dt = 0.4 and 0.2 x the critical step. The critical step (it depends on the
           mesh and, under the penalty law, on kn) is read from the CLI's refusal of dt = 1 s
           ("above the critical step X s"). The run lasts until the touch plus 3 L / c.

Per run: the contact time t_c (the first touch to the last separation in events.csv) against
2 L / c, the observed order of its error between successive meshes (log2 of the ratio, the edge
halving), the bars' final velocities of the mass centre (tracks.csv) over v0, the energy drift
(total_end - total_start) / KE_start, where the total counts the onset loss and the tie work as
spent, and the onset loss / KE_start, steps and wall seconds (summary.json), and the CLI's CPU
seconds (user + system, from the children's rusage; the runs take OMP_NUM_THREADS=1).

    python3 bench/cdem_sweep.py build/rockcontact [--quick]

--quick drops the finest mesh, the 0.2 x critical step and the penalty at 1e9 and 1e11.
"""
import argparse
import csv
import json
import math
import os
import pathlib
import re
import resource
import subprocess
import tempfile
import time

SCENE = pathlib.Path(__file__).resolve().parent.parent / "examples/scenes_cdem/bars.json"
CRITICAL = re.compile(r"above the critical step ([0-9.eE+-]+) s")


def laws(quick):
    two_scale = [("two-scale", {"law": "two-scale"}),
                 ("two-scale, subdivide", {"law": "two-scale", "subdivide": True})]
    kns = (1e10,) if quick else (1e9, 1e10, 1e11)
    return two_scale + [(f"penalty, kn = {kn:g} N/m", {"law": "penalty", "kn": kn}) for kn in kns]


class Bars:
    """The analytic figures, read from the scene so that an edited scene stays consistent."""

    def __init__(self, scene):
        striker, target = scene["blocks"]
        material = scene["materials"][striker["material"]]
        xs = [v[0] for v in striker["vertices"]]
        self.length = max(xs) - min(xs)  # m
        self.v0 = striker["velocity"][0]  # m/s
        self.gap = min(v[0] for v in target["vertices"]) - max(xs)  # m
        self.c = math.sqrt(material["youngs_modulus"] / material["density"])  # m/s, bar speed
        self.t_touch = self.gap / self.v0  # s
        self.t_contact = 2 * self.length / self.c  # s
        self.duration = self.t_touch + 3 * self.length / self.c  # s


def write_scene(base, tmp, contact, max_edge, dt, duration):
    scene = json.loads(json.dumps(base))
    scene["contact"] = {"search_tolerance": base["contact"]["search_tolerance"], **contact}
    for block in scene["blocks"]:
        block["mesh"]["max_edge"] = max_edge
    scene["time"] = {"dt": dt, "duration": duration}
    scene["output"] = {"track": [b["id"] for b in scene["blocks"]], "every": 10**9}
    path = tmp / "bars.json"
    path.write_text(json.dumps(scene))
    return path


def critical_step(exe, base, tmp, contact, max_edge):
    path = write_scene(base, tmp, contact, max_edge, 1.0, 1.0)
    out = subprocess.run([exe, "run", str(path), "--out", str(tmp / "probe")],
                         capture_output=True, text=True)
    match = CRITICAL.search(out.stderr)
    if out.returncode == 0 or not match:
        raise RuntimeError(f"dt = 1 s was not refused with a critical step: {out.stderr.strip()}")
    return float(match.group(1))


def run(exe, base, tmp, bars, contact, max_edge, dt):
    """One run's figures, or {"error": message} when the CLI fails."""
    path = write_scene(base, tmp, contact, max_edge, dt, bars.duration)
    out_dir = tmp / "run"
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    out = subprocess.run([exe, "run", str(path), "--out", str(out_dir)], capture_output=True, text=True,
                         env={**os.environ, "OMP_NUM_THREADS": "1"})
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = after.ru_utime + after.ru_stime - before.ru_utime - before.ru_stime
    if out.returncode != 0:
        lines = out.stderr.strip().splitlines()
        return {"error": lines[-1] if lines else f"exit code {out.returncode}"}
    events = list(csv.DictReader((out_dir / "events.csv").read_text().splitlines()))
    touches = [float(e["t"]) for e in events if e["event"] == "touch"]
    separations = [float(e["t"]) for e in events if e["event"] == "separate"]
    final = {}
    for row in csv.DictReader((out_dir / "tracks.csv").read_text().splitlines()):
        final[row["block"]] = float(row["vx"])
    striker, target = (b["id"] for b in base["blocks"])
    summary = json.loads((out_dir / "summary.json").read_text())
    start, end = summary["energy"]["start"], summary["energy"]["end"]
    contact_time = None
    if touches and separations and separations[-1] > touches[-1]:
        contact_time = separations[-1] - touches[0]
    return {"touches": len(touches), "contact_time": contact_time,
            "striker": final[striker] / bars.v0, "target": (final[target] - bars.v0) / bars.v0,
            "drift": (end["total"] - start["total"]) / start["kinetic"],
            "onset": end["onset_loss"] / start["kinetic"],
            "steps": summary["steps"], "wall": summary["wall_seconds"], "cpu": cpu}


def table(exe, base, tmp, bars, contact, meshes, dt_factors):
    print("| max_edge (m) | dt / dt_crit | dt (s) | touches | t_c (ms) | (t_c − 2L/c) / (2L/c) "
          "| order | striker v / v0 | (target v − v0) / v0 | ΔE / KE0 | onset loss / KE0 | steps "
          "| wall s | CPU s |")
    print("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    middle = meshes[len(meshes) // 2]
    cases = [(h, dt_factors[0]) for h in meshes] + [(middle, f) for f in dt_factors[1:]]
    critical = {h: critical_step(exe, base, tmp, contact, h) for h in meshes}
    previous_error = None
    for h, factor in cases:
        dt = factor * critical[h]
        r = run(exe, base, tmp, bars, contact, h, dt)
        lead = f"| {h:g} | {factor:g} | {dt:.3g} |"
        if "error" in r:
            print(f"{lead} failed: {r['error']} |" + " |" * 10)
            previous_error = None
            continue
        if r["contact_time"] is None:
            timing, error, order = "no separation", "", ""
            previous_error = None
        else:
            e = (r["contact_time"] - bars.t_contact) / bars.t_contact
            timing, error = f"{r['contact_time'] * 1e3:.4f}", f"{e:+.2%}"
            mesh_row = factor == dt_factors[0]
            order = (f"{math.log2(abs(previous_error) / abs(e)):.2f}"
                     if mesh_row and previous_error and e != 0 else "")
            previous_error = e if mesh_row else None
        print(f"{lead} {r['touches']} | {timing} | {error} | {order} | {r['striker']:+.4f} | "
              f"{r['target']:+.2%} | {r['drift']:+.3%} | {r['onset']:.3%} | {r['steps']} | "
              f"{r['wall']:.2f} | {r['cpu']:.2f} |")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("exe", nargs="?", default="build/rockcontact", help="the rockcontact executable")
    parser.add_argument("--quick", action="store_true", help="two meshes, two steps, one penalty")
    args = parser.parse_args()
    meshes = (0.05, 0.025) if args.quick else (0.05, 0.025, 0.0125)
    dt_factors = (0.8, 0.4) if args.quick else (0.8, 0.4, 0.2)
    base = json.loads(SCENE.read_text())
    bars = Bars(base)
    print(f"Saint-Venant's bars ({SCENE.name}): L = {bars.length:g} m, c = {bars.c:.1f} m/s, "
          f"2L/c = {bars.t_contact * 1e3:.4f} ms, touch at {bars.t_touch * 1e3:.4f} ms, "
          f"runs of {bars.duration * 1e3:.4f} ms.")
    print(f"Load average at the start: {open('/proc/loadavg').read().split()[0]} (2 cores: wall "
          "seconds wait on other jobs; CPU seconds, the CLI's own user + system time on one "
          "thread, less so).")
    started = time.monotonic()
    with tempfile.TemporaryDirectory() as name:
        tmp = pathlib.Path(name)
        for title, contact in laws(args.quick):
            print(f"\n{title}:\n")
            table(args.exe, base, tmp, bars, contact, meshes, dt_factors)
    print(f"\nTotal {time.monotonic() - started:.0f} s; load average at the end: "
          f"{open('/proc/loadavg').read().split()[0]}.")


if __name__ == "__main__":
    main()
