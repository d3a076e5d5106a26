#!/usr/bin/env python3
"""Ratio table for peer_bench: ns/pair and ratios against the naive clip, Box2D and CGAL.

Reads the JSON that peer_bench writes with --benchmark_out (run with
--benchmark_repetitions=5 --benchmark_report_aggregates_only=true) and prints, for each pool,
a Markdown table of the median ns/pair of every benchmark and its ratio to the baselines,
then the performance targets on the 3-8 pool with met/missed. Standard library only.

    python3 bench/peer_table.py peer.json

With --run BINARY it first runs the benchmark itself, pinned to one core:

    python3 bench/peer_table.py peer.json --run build/bench/peer_bench
"""

import argparse
import json
import os
import subprocess
import sys

OURS = ["classify", "overlap_ip", "force_exact", "force_paper"]
POLICIES = ["float", "filtered", "exact"]
BASELINES = ["naive_clip", "box2d_manifold", "cgal_intersection", "cgal_minkowski"]
POOLS = ["3-8", "3-12"]


def run(binary, out, cpu):
    command = ["taskset", "-c", str(cpu), binary, "--benchmark_repetitions=5",
               "--benchmark_report_aggregates_only=true", "--benchmark_min_time=0.2",
               f"--benchmark_out={out}", "--benchmark_out_format=json"]
    print("$", " ".join(command), file=sys.stderr)
    print("load before:", os.getloadavg(), file=sys.stderr)
    subprocess.run(command, check=True, stdout=sys.stderr)
    print("load after:", os.getloadavg(), file=sys.stderr)


def medians(report):
    """name -> (median ns/pair, relative spread, median fallback_rate, median interval_rate)."""
    by_name = {}
    for entry in report["benchmarks"]:
        if entry.get("run_type") != "aggregate":
            continue
        slot = by_name.setdefault(entry["run_name"], {})
        slot[entry["aggregate_name"]] = entry
    rows = {}
    for name, aggregates in by_name.items():
        median = aggregates["median"]["per_pair"] * 1e9
        spread = aggregates["stddev"]["per_pair"] * 1e9 / median if "stddev" in aggregates else 0.0
        rows[name] = (median, spread, aggregates["median"].get("fallback_rate", 0.0),
                      aggregates["median"].get("interval_rate", 0.0))
    return rows


def ratio(rows, name, baseline):
    if name not in rows or baseline not in rows:
        return ""
    return f"{rows[name][0] / rows[baseline][0]:.3g}"


def table(rows, pool):
    names = [f"{what}/{policy}/{pool}" for what in OURS for policy in POLICIES]
    names += [f"{baseline}/{pool}" for baseline in BASELINES]
    naive, box2d, cgal = (f"{b}/{pool}" for b in BASELINES[:3])
    lines = ["| benchmark | ns/pair (median) | ± stddev | × naive clip | × Box2D | × CGAL intersection |",
             "|---|---:|---:|---:|---:|---:|"]
    for name in names:
        if name not in rows:
            continue
        median, spread = rows[name][:2]
        lines.append(f"| `{name}` | {median:,.1f} | {100 * spread:.1f}% | {ratio(rows, name, naive)} | "
                     f"{ratio(rows, name, box2d)} | {ratio(rows, name, cgal)} |")
    return "\n".join(lines)


def targets(rows, context):
    def ns(name):
        return rows[name][0]

    fallback = max(rows[f"{what}/filtered/{pool}"][2] for what in OURS for pool in POOLS)
    interval = max(rows[f"{what}/filtered/{pool}"][3] for what in OURS for pool in POOLS)
    fallback_pairs = max(float(context.get(f"pool {pool} fallback_pair_fraction", "nan")) for pool in POOLS)
    # The targets of the predicate-engine issue: a must (the first bound) and a goal (the
    # second), both read `value <= bound`; >= targets are stored negated.
    checks = [
        ("filtered overlap + IP ≤ 2 × naive clip (must; goal 1.3 ×)",
         ns("overlap_ip/filtered/3-8") / ns("naive_clip/3-8"), 2.0, 1.3, "×"),
        ("filtered overlap + IP ≤ 2.5 × Box2D manifold (must; goal 2 ×)",
         ns("overlap_ip/filtered/3-8") / ns("box2d_manifold/3-8"), 2.5, 2.0, "×"),
        ("filtered overlap + IP + force (exact demarcation) ≤ 5.5 × naive clip (must; goal 500 ns)",
         ns("force_exact/filtered/3-8") / ns("naive_clip/3-8"), 5.5, 500.0 / ns("naive_clip/3-8"), "×"),
        ("CGAL intersection / exact overlap + IP ≥ 5 (must; goal 20)",
         -ns("cgal_intersection/3-8") / ns("overlap_ip/exact/3-8"), -5.0, -20.0, "×"),
        ("exact force (exact demarcation) ≤ 50 µs (goal)",
         ns("force_exact/exact/3-8") / 1e3, None, 50.0, " µs"),
        ("interval fallbacks per predicate call < 1e-3 (both pools)", interval, 1e-3, None, ""),
        ("exact fallbacks per predicate call < 1e-3 (both pools)", fallback, 1e-3, None, ""),
        ("fraction of pairs with an exact fallback < 1e-3 (both pools)", fallback_pairs, 1e-3, None, ""),
        # CGAL's Epeck filters with intervals and goes exact only on demand, like our Filtered.
        ("reference, no target: CGAL intersection / filtered overlap + IP",
         ns("cgal_intersection/3-8") / ns("overlap_ip/filtered/3-8"), None, None, "×"),
    ]
    lines = ["| target (3-8 pool) | measured | must | goal |", "|---|---:|---|---|"]

    def verdict(value, bound):
        return "" if bound is None else ("met" if value <= bound else "missed")

    for label, value, must, goal, unit in checks:
        negated = (must is not None and must < 0) or (goal is not None and goal < 0)
        shown = -value if negated else value
        lines.append(f"| {label} | {shown:.4g}{unit} | {verdict(value, must)} | {verdict(value, goal)} |")
    return "\n".join(lines)


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("json", help="peer_bench --benchmark_out file")
    parser.add_argument("--run", metavar="BINARY", help="run this peer_bench first, writing the JSON")
    parser.add_argument("--cpu", type=int, default=1, help="core to pin the run to (taskset -c)")
    args = parser.parse_args()
    if args.run:
        run(args.run, args.json, args.cpu)
    with open(args.json, encoding="utf-8") as f:
        report = json.load(f)
    context = report["context"]
    rows = medians(report)
    print(f"load average at start of run: {context.get('load_avg')}")
    for pool in POOLS:
        print(f"\npool {pool}: {context.get('pool pairs')} pairs, seed {context.get('pool seed')}, "
              f"overlap fraction {float(context.get(f'pool {pool} overlap_fraction', 'nan')):.3f}\n")
        print(table(rows, pool))
    print()
    print(targets(rows, context))


if __name__ == "__main__":
    main()
