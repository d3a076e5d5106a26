#!/usr/bin/env python3
"""The implicit 3D DDA on a family of rock wedges against Hoek & Bray (dynamics/apps/wedge_family.hpp).

For a seed, a count and a friction angle, `wedge_family_scenes` (bench/wedge_family_scenes.cpp)
writes the family's scenes (seed 001 6.1's slope block cut by two random joints through a crest
point: a fixed, non-convex base and the tetrahedral wedge) with their references. Then, per case:

  factor of safety: `rockcontact safety-factor SCENE --block wedge -o -` (strength reduction,
                    trials of 1 s) against Hoek & Bray's limit equilibrium on the same joints;
  slide (FS < 1):   `rockcontact run SCENE` for the scene's 1 s, the wedge centroid's displacement
                    along the line of intersection (tracks.csv) against 1/2 g sin(psi_i) (1 - FS) t^2,
                    up to the case's slide_time_s (wedge_slide_time: 1 s, or less where the wedge
                    would reach the free face and tip over its edge, or could no longer slide
                    without turning).

Prints Markdown tables and the worst errors; exits 1 when a command failed or a factor of safety
is only a bound (status stable_at_max or slides_at_min). Standard library only.

    python3 bench/wedge_family.py --seed 1 --count 10 --phi 40
    python3 bench/wedge_family.py --seed 1 --count 5 --phi 20 --kn 1e10 --dt 1e-4
    python3 bench/wedge_family.py --seed 1 --count 10 --phi 40 --kn auto
    python3 bench/wedge_family.py --seed 1 --count 10 --phi 20 --kn auto --only slides

The same seed gives the same wedges at every friction angle.
"""
import argparse
import csv
import json
import os
import pathlib
import subprocess
import sys
import tempfile
import time

ROOT = pathlib.Path(__file__).resolve().parent.parent


def arguments():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--seed", type=int, default=1, help="the family's seed (default 1)")
    p.add_argument("--count", type=int, default=10, help="number of wedges (default 10)")
    p.add_argument("--phi", type=float, default=40.0, help="friction angle on both joints, degrees (default 40)")
    p.add_argument("--kn", type=penalty, default=1e10,
                   help="normal penalty, N/m, or auto (the scenes then leave kn and kt to the library); "
                        "kt = kn / 10 (default 1e10)")
    p.add_argument("--dt", type=float, default=1e-4, help="time step, s (default 1e-4)")
    p.add_argument("--exe", default=str(ROOT / "build" / "rockcontact"), help="the rockcontact executable")
    p.add_argument("--scenes-exe", help="wedge_family_scenes (default: bench/ beside --exe)")
    p.add_argument("--keep", help="write the scenes and runs here instead of a temporary directory")
    p.add_argument("--only", choices=["fs", "slides"], help="run only the factors of safety or only the slides")
    return p.parse_args()


def penalty(text):
    return text if text == "auto" else float(text)


def timed(command):
    start = time.monotonic()
    out = subprocess.run(command, capture_output=True, text=True,
                         env={**os.environ, "OMP_WAIT_POLICY": "passive"})
    return out, time.monotonic() - start


def failure(what, out):
    lines = (out.stderr or out.stdout).strip().splitlines()
    return f"{what}: exit {out.returncode}: {lines[-1] if lines else '(no output)'}"


def joints(case):
    a, b = case["joint_a"], case["joint_b"]
    return f"{a['dip_deg']:g}/{a['dip_direction_deg']:g}, {b['dip_deg']:g}/{b['dip_direction_deg']:g}"


def slide(case, tracks):
    """The wedge centroid's displacement along the line of intersection, the time, the reference."""
    rows = [r for r in csv.DictReader(open(tracks)) if r["block"] == "wedge"]
    # Up to the case's slide_time_s (wedge_slide_time: before the wedge reaches the free face).
    window = float(rows[0]["t"]) + case["reference"]["slide_time_s"] + 1e-9
    first, last = rows[0], [r for r in rows if float(r["t"]) <= window][-1]
    line = case["reference"]["intersection"]
    moved = sum((float(last[k]) - float(first[k])) * line[i] for i, k in enumerate("xyz"))
    t = float(last["t"]) - float(first["t"])
    return moved, t, 0.5 * case["reference"]["slide_acceleration_m_s2"] * t * t


def safety_factors(args, cases, work, failures):
    print(f"Factor of safety, phi = {args.phi:g} deg, kn = {args.kn} N/m, kt = kn/10, dt = {args.dt:g} s "
          f"(`rockcontact safety-factor`, trials of 1 s)\n")
    print("| case | joints A, B (dip/dir) | plunge/trend | V (m³) | Hoek–Bray FS | DDA FS | status | error | trials | wall s |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    errors = []
    for k, case in enumerate(cases):
        ref = case["reference"]
        out, wall = timed([args.exe, "safety-factor", str(work / case["scene"]), "--block", "wedge", "-o", "-"])
        head = (f"| {k} | {joints(case)} | {ref['plunge_deg']:.1f}/{ref['trend_deg']:.1f} | {ref['volume_m3']:.1f} "
                f"| {ref['factor_of_safety']:.4f} |")
        if out.returncode != 0:
            failures.append(failure(f"case {k} safety-factor", out))
            print(f"{head} — | exit {out.returncode} | — | — | {wall:.1f} |", flush=True)
            continue
        result = json.loads(out.stdout)
        if result["status"] != "converged":  # FS outside the bisection's [0.1, 10]: a bound, not a value
            failures.append(f"case {k} safety-factor: {result['status']}")
        fs = result["factor_of_safety"]
        error = (fs - ref["factor_of_safety"]) / ref["factor_of_safety"]
        errors.append((abs(error), error, k))
        print(f"{head} {fs:.4f} | {result['status']} | {error:+.2%} | {result['iterations']} | {wall:.1f} |", flush=True)
    return errors


def slides(args, cases, work, failures):
    sliding = [(k, c) for k, c in enumerate(cases) if c["reference"]["factor_of_safety"] < 1]
    # A wedge that would have to turn from the start has no slide reference (slide_time_s 0).
    for k, c in sliding:
        if c["reference"]["slide_time_s"] == 0:
            print(f"case {k}: FS {c['reference']['factor_of_safety']:.4f} but it cannot slide without turning "
                  f"(support {c['reference']['sliding_support_of_weight']:.1%}): no slide reference")
    sliding = [(k, c) for k, c in sliding if c["reference"]["slide_time_s"] > 0]
    if not sliding:
        return []
    print(f"\nSlide along the line of intersection, FS < 1 (`rockcontact run`, 1 s, measured up to t: 1 s or "
          f"0.8 of the time the centroid takes to reach the free face or to where the wedge would have to turn): "
          f"1/2 g sin(psi_i) (1 - FS) t^2; support: the least corner force that lets it slide without turning, "
          f"of its weight, at the start\n")
    print("| case | Hoek–Bray FS | plunge | support | t (s) | reference (m) | DDA (m) | error | wall s |")
    print("|---|---|---|---|---|---|---|---|---|")
    errors = []
    for k, case in sliding:
        ref = case["reference"]
        out_dir = work / f"run_{k}"
        out, wall = timed([args.exe, "run", str(work / case["scene"]), "--out", str(out_dir)])
        head = (f"| {k} | {ref['factor_of_safety']:.4f} | {ref['plunge_deg']:.1f} "
                f"| {ref['sliding_support_of_weight']:.1%} |")
        if out.returncode != 0:
            failures.append(failure(f"case {k} run", out))
        if not (out_dir / "tracks.csv").exists():
            print(f"{head} — | — | exit {out.returncode} | — | {wall:.1f} |", flush=True)
            continue
        moved, t, expected = slide(case, out_dir / "tracks.csv")
        error = (moved - expected) / expected
        errors.append((abs(error), error, k))
        note = "" if out.returncode == 0 else f" (exit {out.returncode})"
        print(f"{head} {t:.3f} | {expected:.4f} | {moved:.4f} | {error:+.2%}{note} | {wall:.1f} |", flush=True)
    return errors


def main() -> int:
    args = arguments()
    scenes_exe = args.scenes_exe or str(pathlib.Path(args.exe).parent / "bench" / "wedge_family_scenes")
    with tempfile.TemporaryDirectory() as tmp:
        work = pathlib.Path(args.keep or tmp)
        every = max(1, round(0.01 / args.dt))  # about 100 records a second
        subprocess.run([scenes_exe, "--seed", str(args.seed), "--count", str(args.count), "--phi", repr(args.phi),
                        "--kn", "1e10" if args.kn == "auto" else repr(args.kn), "--dt", repr(args.dt),
                        "--duration", "1", "--every", str(every), "--out", str(work)], check=True)
        cases = json.loads((work / "cases.json").read_text())
        if args.kn == "auto":
            for case in cases:
                scene = json.loads((work / case["scene"]).read_text())
                del scene["contact"]["kn"], scene["contact"]["kt"]
                (work / case["scene"]).write_text(json.dumps(scene, indent=1))
        print(f"Wedge family: seed {args.seed}, {len(cases)} cases (dynamics/apps/wedge_family.hpp)\n")
        failures = []
        fs_errors = safety_factors(args, cases, work, failures) if args.only != "slides" else []
        slide_errors = slides(args, cases, work, failures) if args.only != "fs" else []
    print()
    if fs_errors:
        worst = max(fs_errors)
        print(f"worst factor-of-safety error: {worst[1]:+.2%} (case {worst[2]}); "
              f"mean |error| {sum(e[0] for e in fs_errors) / len(fs_errors):.2%}")
    if slide_errors:
        worst = max(slide_errors)
        print(f"worst slide error: {worst[1]:+.2%} (case {worst[2]})")
    for f in failures:
        print(f"failed: {f}")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
