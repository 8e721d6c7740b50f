#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""The contact engine against issue 4's goals and CHAI3D 3.3's reference figures:
`hapticad bench-mesh` on icospheres of 9,680, 100,820 and 1,003,520 triangles (radius
50 mm), point and 1 mm sphere proxies, in mm and (at 1M) in metres; each run repeated
and the median of each figure kept. Prints a Markdown table (and --json the runs), then
the contact ticks grouped by how far the contact moved since the tick before (bench-mesh's
`tick_us_by_move`): what share of the ticks crossed more triangles, and what those cost.

    benchmarks/core/rendering/contact_goals.py [--hapticad build/bin/hapticad] [--repeat 3]
        [--convex-pieces on|off] [--warm-ahead N]
"""
import argparse
import json
import statistics
import subprocess

SIZES = [9680, 100820, 1003520]


MOVES = ("stayed", "next", "second", "further")


def run(hapticad, triangles, proxy, units, ticks, convex_pieces, warm_ahead):
    out = subprocess.run([hapticad, "bench-mesh", "--icosphere", str(triangles), "--proxy", proxy,
                          "--units", units, "--ticks", str(ticks), "--convex-pieces", convex_pieces,
                          "--warm-ahead", str(warm_ahead), "--json"],
                         capture_output=True, text=True, check=True)
    return json.loads(out.stdout)


def median_of(runs, *keys):
    values = []
    for r in runs:
        v = r
        for k in keys:
            v = v[k]
        values.append(v)
    return statistics.median(values)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--hapticad", default="build/bin/hapticad")
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--ticks", type=int, default=20000)
    parser.add_argument("--json", action="store_true")
    parser.add_argument("--convex-pieces", choices=("on", "off"), default="on",
                        help="off: every sweep walks the grid or the tree (to compare)")
    parser.add_argument("--warm-ahead", type=int, default=0,
                        help="bench-mesh's diagnostic: each block of N ticks run untimed first, so "
                             "the timed ticks find their data in the caches")
    args = parser.parse_args()
    configs = [(n, p, "mm") for n in SIZES for p in ("point", "sphere:1")]
    configs += [(SIZES[-1], p, "m") for p in ("point", "sphere:1")]
    rows, raw = [], []
    for n, proxy, units in configs:
        runs = [run(args.hapticad, n, proxy, units, args.ticks, args.convex_pieces, args.warm_ahead)
                for _ in range(args.repeat)]
        raw.append({"triangles": n, "proxy": proxy, "units": units, "runs": runs})
        rows.append((n, proxy, units, runs))
    if args.json:
        print(json.dumps(raw, indent=1))
        return
    print("| triangles | proxy | units | tick p50 / p99 / p999 (us) | build (ms) | repair (ms) | bytes/triangle "
          "| contact ticks | pop-through | max force (N) |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for n, proxy, units, runs in rows:
        print(f"| {n:,} | {proxy} | {units} | {median_of(runs, 'tick_us', 'p50'):.2f} / "
              f"{median_of(runs, 'tick_us', 'p99'):.2f} / {median_of(runs, 'tick_us', 'p999'):.2f} "
              f"| {median_of(runs, 'build_ms'):.0f} | {median_of(runs, 'repair_ms'):.0f} "
              f"| {runs[0]['bytes_per_triangle']:.0f} | {min(r['contact_ticks'] for r in runs)} / {runs[0]['ticks']} "
              f"| {max(r['pop_through'] for r in runs)} | {max(r['max_force_n'] for r in runs):.3f} |")
    print()
    print("| triangles | proxy | units | " +
          " | ".join(f"{m}: share, p50 / p99 (us)" for m in MOVES) + " |")
    print("|---|---|---|" + "---|" * len(MOVES))
    for n, proxy, units, runs in rows:
        cells = []
        total = sum(r["tick_us_by_move"][k]["ticks"] for r in runs for k in MOVES)
        for m in MOVES:
            share = sum(r["tick_us_by_move"][m]["ticks"] for r in runs) / max(total, 1)
            cells.append(f"{100 * share:.2f} %, {median_of(runs, 'tick_us_by_move', m, 'p50'):.2f} / "
                         f"{median_of(runs, 'tick_us_by_move', m, 'p99'):.2f}")
        print(f"| {n:,} | {proxy} | {units} | " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main()
