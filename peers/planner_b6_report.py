#!/usr/bin/env python3
"""B6 table for every size, including the capped proof attempts of n >= 160, and the
simulator's own sol problems (`sol_<stem>.json`, criterion `prove_sol/<stem>`).

`planner_cpsat.py report` reads criterion's estimate of `prove_n{N}/{seed}` for every instance
and stops at the first one missing; since `benches/planner.rs` times a 160- or 320-activity
proof only when its capped attempt succeeds, this script prints the same table but takes the
planner's side from the bench's `n{N}_seed{S}.planner.json` when criterion has no estimate
(status, value, bound, nodes and the cap), and says "not proven within ..." honestly.

Usage:
  planner_b6_report.py --peers CPSAT.json --criterion DIR --dump DIR
(CPSAT.json = `planner_cpsat.py solve --out`; DIR = the bench's SOLSIM_PLANNER_DUMP directory)
"""
import argparse
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from planner_cpsat import criterion_ms  # noqa: E402

MICRO = 1e6


def tiers(v):
    return f"{v[0] / MICRO:g} / {v[1] / MICRO:g}"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--peers", required=True)
    ap.add_argument("--criterion", required=True)
    ap.add_argument("--dump", required=True)
    args = ap.parse_args()
    with open(args.peers) as f:
        peers = json.load(f)
    by = {(r["file"], r["workers"]): r for r in peers}
    def order(name):
        # B6 instances by size, then the simulator's sol problems (`sol_<stem>.json`).
        if name.startswith("sol_"):
            return (1, 0, name)
        return (0, int(name.split("_")[0][1:]), name)

    files = sorted({r["file"] for r in peers}, key=order)
    print("| instance | planner: proven optimum, ms | CP-SAT 1 worker, ms (status) "
          "| CP-SAT 2 workers, ms (status) | value tier 1 / tier 2: planner, CP-SAT 1 w | "
          "ours / CP-SAT 1w |")
    print("|---|---|---|---|---|---|")
    for name in files:
        stem = name[: -len(".json")]
        if stem.startswith("sol_"):
            bench, param = "prove_sol", stem[len("sol_"):]
        else:
            n, seed = stem.split("_")
            bench, param = f"prove_{n}", seed[len("seed"):]
        with open(os.path.join(args.dump, stem + ".planner.json")) as f:
            pl = json.load(f)
        ours = None
        if pl["status"] == "Optimal":
            try:
                ours = criterion_ms(args.criterion, bench, param)
            except OSError:
                pass
        if ours is not None:
            ours_cell = f"{ours:.2f}" if ours < 10 else f"{ours:.1f}"
        elif pl["status"] == "Optimal":
            ours_cell = f"proven, not timed by criterion ({pl['nodes']} nodes)"
        else:
            cap = pl.get("cap", {})
            gap = (pl["bound_micro"][0] - pl["value_micro"][0]) / MICRO
            ours_cell = (f"not proven within {cap.get('nodes', '?')} nodes / {cap.get('time_s', '?')} s "
                         f"({pl['nodes']} nodes, {cap.get('search_ms', float('nan')) / 1e3:.1f} s): "
                         f"bound t1 {pl['bound_micro'][0] / MICRO:g}, gap t1 {gap:g}")
        r1, r2 = by.get((name, 1)), by.get((name, 2))

        def cell(r):
            if not r:
                return "–"
            return (f"{r['wall_ms_median']:.1f} [{r['wall_ms_min']:.1f}–{r['wall_ms_max']:.1f}] "
                    f"({'/'.join(sorted(set(r['status'])))})")

        both_opt = pl["status"] == "Optimal" and r1 and r1["status"][-1] == "OPTIMAL"
        if r1 and both_opt:
            eq = "equal" if pl["value_micro"] == r1["value_micro"] else "DIFFER"
        else:
            eq = "not both proven"
        v1 = tiers(r1["value_micro"]) if r1 else "–"
        ratio = f"{ours / r1['wall_ms_median']:.3f}" if (ours is not None and r1) else "–"
        print(f"| {stem} | {ours_cell} | {cell(r1)} | {cell(r2)} | "
              f"{tiers(pl['value_micro'])}, {v1} ({eq}) | {ratio} |")


if __name__ == "__main__":
    main()
