#!/usr/bin/env python3
"""B6 anytime quality: the value CP-SAT reaches within a time budget on the planner's instances,
and the table + figure comparing it with the planner's own anytime runs.

The model is planner_cpsat.py's (`build` is imported, not copied), so both sides solve the same
problem; the instances are the JSON files written by
`cargo run -p planner --release --example anytime -- --dump DIR` (or the bench's
SOLSIM_PLANNER_DUMP), and the planner's side is that example's `--out` JSON.

Usage:
  planner_anytime.py solve FILE.json... [--budgets-ms 1 10 100 1000] [--workers 1 2]
                     [--repeat 3] --out F
  planner_anytime.py report --planner ANYTIME.json --cpsat F [--known CPSAT.json] [--svg F]

Budget semantics (CP-SAT). `max_time_in_seconds` = budget / 1000 is CP-SAT's own wall-clock
limit: it covers everything inside the C++ solve call -- model loading and validation, presolve,
the search and the postsolve of the last solution -- as measured by CP-SAT's timer (reported as
`solver_wall_ms` = CpSolver.wall_time). It does NOT cover reading the JSON and building the model
in Python (`build_ms`, once per file: the same CpModel is solved by every run), nor the hand-off
of the model proto from Python to C++ (`call_ms` - `solver_wall_ms`). The planner's
`time_budget` is checked inside its search only; its example reports the wall time of the whole
`plan` call (instance building included). Neither side stops exactly at the budget: see the
overrun table of `report`.

Value per tier: planner_cpsat.build states the lexicographic tiers as one weighted sum (weight of
a tier > the largest sum of all lower tiers). The weights are read back from the model's
objective (coefficient / utility, checked equal within a tier), the objective value is decoded to
whole points per tier by `divmod`, tier 1 first, and checked against the sum over the chosen
activities (exit 1 on a difference); CP-SAT's best bound is decoded the same way (its tier-1
part, floor(bound / w1), is a valid tier-1 bound; the lower tiers' parts are not bounds).
Integer-point utilities (B6) only.
"""
import argparse
import json
import math
import os
import statistics
import sys
import time
import xml.etree.ElementTree as ET

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from peer_common import ensure_venv  # noqa: E402

MICRO = 1_000_000


def normalise(built):
    """(model, [(presence literal, tier index 0 = tier 1, utility in micro-points)], campaign
    utilities) from planner_cpsat.build, whose return value has had two shapes: (m, pres, start,
    tier 1-based, utility in points) and (m, pres, start, tasks, camp_util, info)."""
    m, pres = built[0], built[1]
    if len(built) == 5:
        tiers, utils = [t - 1 for t in built[3]], [u * MICRO for u in built[4]]
        camps = []
    else:
        tiers, utils = [t["tier"] for t in built[3]], [t["util"] for t in built[3]]
        camps = built[4]
    return m, list(zip(pres, tiers, utils)), camps


def tier_units(m, tasks):
    """Objective units per utility point of each tier, read from the model's objective: build
    gives a task of tier t the coefficient w_t x (utility / grain_t), so |coef| x 10^6 / utility
    is the same for every task of the tier (checked), and with the B6 whole-point utilities
    (grain 10^6) it is w_t. The weights exceed every lower-tier sum (lexicographic), so the
    objective decodes by `divmod`, tier 1 first."""
    from fractions import Fraction

    coef = dict(zip(m.proto.objective.vars, m.proto.objective.coeffs))
    units = {}
    for lit, t, u in tasks:
        c = coef.get(lit.index)
        if not u or c is None:
            continue  # no utility, or a fixed (mandatory) task: not in the objective
        r = Fraction(abs(c) * MICRO, u)
        if units.setdefault(t, r) != r:
            raise SystemExit(f"tier {t + 1}: objective coefficients not proportional to utility")
    for t, r in units.items():
        if r.denominator != 1:
            raise SystemExit(f"tier {t + 1}: utilities not whole points: decoding needs them")
    return {t: int(r) for t, r in units.items()}


def decode(objective, units):
    """Whole points per tier (list of 4, tier 1 first) from a weighted objective value."""
    points = [0, 0, 0, 0]
    rest = int(math.floor(objective + 1e-6))
    for t in sorted(units):  # tier 1 first: the largest weight
        points[t], rest = divmod(rest, units[t])
    return points


def solve_file(path, budgets_ms, workers, repeat):
    from ortools.sat.python import cp_model
    from planner_cpsat import build

    clock = time.perf_counter()
    with open(path) as f:
        problem = json.load(f)
    m, tasks, camps = normalise(build(problem))
    build_ms = (time.perf_counter() - clock) * 1e3
    if camps:
        raise SystemExit(f"{path}: campaigns: the objective decoding supports B6 instances only")
    units = tier_units(m, tasks)
    out = {"file": os.path.basename(path), "n_tasks": len(tasks), "build_ms": build_ms,
           "tier_weights": {str(t + 1): w for t, w in units.items()}, "runs": []}
    for w in workers:
        for budget in budgets_ms:
            for rep in range(repeat):
                solver = cp_model.CpSolver()
                solver.parameters.num_workers = w
                solver.parameters.max_time_in_seconds = budget / 1e3
                t = time.perf_counter()
                status = solver.solve(m)
                call_ms = (time.perf_counter() - t) * 1e3
                found = status in (cp_model.OPTIMAL, cp_model.FEASIBLE)
                r = {"workers": w, "budget_ms": budget, "repeat": rep,
                     "status": solver.status_name(status), "found": found,
                     "solver_wall_ms": solver.wall_time * 1e3, "call_ms": call_ms}
                if found:
                    pts = decode(solver.objective_value, units)
                    direct = [0, 0, 0, 0]  # the plan's own sum, mandatory tasks included
                    for lit, tier, u in tasks:
                        if u and solver.boolean_value(lit):
                            direct[tier] += u
                    if [p * MICRO for p in pts] != direct:
                        raise SystemExit(f"{path}: objective decodes to {pts} points, the plan "
                                         f"sums to {direct} micro-points")
                    r["value_micro"] = direct
                    r["bound_micro"] = [p * MICRO for p in decode(solver.best_objective_bound, units)]
                print(json.dumps({"file": out["file"], **r}), flush=True)
                out["runs"].append(r)
    return out


# ---------------------------------------------------------------------------------------------
# report

def lex_key(v):
    return tuple(v) if v is not None else (-1,)


def summarise(values):
    """(median, min, max) of a list of per-tier values (None = no solution), lexicographic."""
    vs = sorted(values, key=lex_key)
    return vs[len(vs) // 2], vs[0], vs[-1]


def pts(v):
    return [x / MICRO for x in v] if v is not None else None


def fmt_v(v):
    return "–" if v is None else f"{v[0]:g} / {v[1]:g}"


def cell(med, lo, hi, extra=""):
    """'t1 / t2' of the median; the tier-1 range when the runs differ."""
    if med is None and lo is None and hi is None:
        return "no solution" + extra
    s = fmt_v(pts(med)) if med is not None else "no solution"
    if lex_key(lo) != lex_key(hi):
        # The tier-1 range, or the tier-2 range when tier 1 is the same in every run.
        k = 1 if (lo is not None and hi is not None and lo[0] == hi[0]) else 0
        a = "none" if lo is None else f"{lo[k] / MICRO:g}"
        b = "none" if hi is None else f"{hi[k] / MICRO:g}"
        s += f" [t{k + 1} {a}–{b}]"
    return s + extra


def load_report_data(planner_path, cpsat_path, known_path):
    with open(planner_path) as f:
        planner = json.load(f)
    cpsat = []
    if cpsat_path:
        with open(cpsat_path) as f:
            cpsat = json.load(f)
    cp_by_file = {c["file"]: c for c in cpsat}
    known = {}
    if known_path:  # planner_cpsat.py solve --out: longer CP-SAT runs
        with open(known_path) as f:
            for r in json.load(f):
                known.setdefault(r["file"], []).append(r)
    return planner, cp_by_file, known


def best_known(inst, cp, known):
    """(value_micro, proven?, tier-1 upper bound in points or None) from every run we have."""
    cands, proven, ub = [], False, []
    proof = inst["proof"]
    cands.append(proof["value_micro"])
    ub.append(proof["bound_micro"][0] / MICRO)
    if proof["status"] == "Optimal":
        proven = True
    for b in inst["budgets"]:
        for r in b["runs"]:
            cands.append(r["value_micro"])
            ub.append(r["bound_micro"][0] / MICRO)
            proven |= r["status"] == "Optimal"
    for r in (cp or {}).get("runs", []):
        if r["found"]:
            cands.append(r["value_micro"])
            ub.append(r["bound_micro"][0] / MICRO)
            proven |= r["status"] == "OPTIMAL"
    for r in known.get(inst["file"], []):
        if any(s in ("OPTIMAL", "FEASIBLE") for s in r["status"]):
            cands.append(r["value_micro"])
        proven |= "OPTIMAL" in r["status"]
    return max(cands, key=lex_key), proven, min(ub) if ub else None


def report(args):
    planner, cp_by_file, known = load_report_data(args.planner, args.cpsat, args.known)
    rows, series = [], {}
    print("| instance | budget | planner (tier 1 / tier 2) | planner bound t1, nodes "
          "| CP-SAT 1 worker | CP-SAT 2 workers | best known (tier 1 / tier 2) |")
    print("|---|---|---|---|---|---|---|")
    overrun = {}
    for inst in sorted(planner["instances"], key=lambda i: (i["n"], i["seed"])):
        cp = cp_by_file.get(inst["file"])
        best, proven, ub = best_known(inst, cp, known)
        best_t1 = best[0] / MICRO
        best_s = f"{fmt_v(pts(best))} " + ("(proven)" if proven else f"(not proven; t1 ≤ {ub:g})")
        for b in inst["budgets"]:
            ms = b["budget_ms"]
            med, lo, hi = (b[k]["value_micro"] for k in ("median", "min", "max"))
            opt = " (opt)" if b["median"]["status"] == "Optimal" else ""
            pcell = cell(med, lo, hi, opt)
            bcell = f"{b['median']['bound_micro'][0] / MICRO:g}, {b['median']['nodes']}"
            key = ("planner", inst["n"], ms)
            overrun[key] = max(overrun.get(key, 0), max(r["wall_ms"] for r in b["runs"]))
            key = ("planner search", inst["n"], ms)
            overrun[key] = max(overrun.get(key, 0), max(r["search_ms"] for r in b["runs"]))
            series.setdefault(("planner", inst["n"]), {}).setdefault(ms, []).append(
                med[0] / MICRO / best_t1 if best_t1 else 1.0)
            ccells = []
            for w in (1, 2):
                runs = [r for r in (cp or {}).get("runs", [])
                        if r["workers"] == w and r["budget_ms"] == ms]
                if not runs:
                    ccells.append("–")
                    continue
                vals = [r.get("value_micro") if r["found"] else None for r in runs]
                cmed, clo, chi = summarise(vals)
                stat = sorted({r["status"] for r in runs})
                extra = " (opt)" if stat == ["OPTIMAL"] else ""
                nf = sum(not r["found"] for r in runs)
                if nf and nf < len(runs):
                    extra += f" ({nf}/{len(runs)} runs no solution)"
                ccells.append(cell(cmed, clo, chi, extra))
                key = (f"CP-SAT {w}w", inst["n"], ms)
                overrun[key] = max(overrun.get(key, 0), max(r["solver_wall_ms"] for r in runs))
                key = (f"CP-SAT {w}w call", inst["n"], ms)
                overrun[key] = max(overrun.get(key, 0), max(r["call_ms"] for r in runs))
                frac = (cmed[0] / MICRO / best_t1 if best_t1 else 1.0) if cmed is not None else 0.0
                series.setdefault((f"CP-SAT {w} worker{'s' if w > 1 else ''}", inst["n"]),
                                  {}).setdefault(ms, []).append(frac)
            print(f"| n = {inst['n']}, seed {inst['seed']} | {ms} ms | {pcell} | {bcell} "
                  f"| {ccells[0]} | {ccells[1]} | {best_s} |")
    print()
    print("Medians of 3 runs (lexicographic, tier 1 first); [t1 a–b] = tier-1 range when runs "
          "differ ([t2 a–b]: same tier 1, tier 2 differs); (opt) = proven optimal in that run; 'best known' = the best value of every "
          "run above, the planner's proof attempt and --known, 'proven' when any of them proved it.")
    print()
    builds = [(c["file"], c["build_ms"]) for c in cp_by_file.values()]
    if builds:
        print("CP-SAT model building in Python (JSON load + planner_cpsat.build; outside "
              "max_time_in_seconds): " + ", ".join(f"{f[:-5]} {ms:.0f} ms" for f, ms in
                                                   sorted(builds, key=lambda x: (int(x[0].split('_')[0][1:]), x[0]))))
        print()
    print("| wall time, max over seeds and runs (ms) | " +
          " | ".join(f"{ms} ms" for ms in planner["budgets_ms"]) + " |")
    print("|---|" + "---|" * len(planner["budgets_ms"]))
    labels = sorted({k[0] for k in overrun}, key=lambda s: (not s.startswith("planner"), s))
    for lab in labels:
        for n in sorted({k[1] for k in overrun}):
            vals = [overrun.get((lab, n, ms)) for ms in planner["budgets_ms"]]
            if all(v is None for v in vals):
                continue
            what = {"planner": "planner `plan` call (instance building included)",
                    "planner search": "planner search (`stats.total_time`)"}.get(
                lab, lab.replace(" call", " solve() call") if lab.endswith("call")
                else lab + " wall_time")
            print(f"| n = {n}: {what} | " + " | ".join("–" if v is None else f"{v:.1f}" for v in vals)
                  + " |")
    if args.svg:
        write_svg(args.svg, series, planner["budgets_ms"])
        ET.parse(args.svg)  # must be well-formed XML
        print(f"\nfigure: {args.svg}")


def write_svg(path, series, budgets):
    """One panel per n: mean over seeds of (median tier-1 value / best known tier 1) against the
    budget on a log axis, one line per solver."""
    ns = sorted({n for (_, n) in series})
    solvers = ["planner", "CP-SAT 1 worker", "CP-SAT 2 workers"]
    colours = {"planner": "#d62728", "CP-SAT 1 worker": "#1f77b4", "CP-SAT 2 workers": "#2ca02c"}
    dashes = {"planner": "", "CP-SAT 1 worker": "", "CP-SAT 2 workers": "6,3"}
    allv = [v for s in series.values() for vs in s.values() for v in vs]
    ymin = min(0.9, math.floor(min(allv) * 10) / 10) if allv else 0.0
    pw, ph, ml, mt, mb, gap = 260, 220, 55, 40, 45, 25
    width = ml + len(ns) * (pw + gap) + 10
    height = mt + ph + mb + 30
    lx0, lx1 = math.log10(min(budgets)), math.log10(max(budgets))
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" '
           f'font-family="sans-serif" font-size="11">',
           f'<rect width="{width}" height="{height}" fill="white"/>',
           f'<text x="{width / 2}" y="16" text-anchor="middle" font-size="13">B6 anytime: tier-1 '
           f'value / best known tier 1 (mean over seeds 1–3 of the median of 3 runs)</text>']
    for k, n in enumerate(ns):
        x0 = ml + k * (pw + gap)
        X = lambda ms: x0 + (math.log10(ms) - lx0) / (lx1 - lx0 or 1) * pw
        Y = lambda f: mt + (1.0 - (f - ymin) / (1.0 - ymin or 1)) * ph
        out.append(f'<rect x="{x0}" y="{mt}" width="{pw}" height="{ph}" fill="none" stroke="#444"/>')
        out.append(f'<text x="{x0 + pw / 2}" y="{mt - 6}" text-anchor="middle">n = {n}</text>')
        for ms in budgets:
            out.append(f'<line x1="{X(ms):.1f}" y1="{mt}" x2="{X(ms):.1f}" y2="{mt + ph}" stroke="#ddd"/>')
            out.append(f'<text x="{X(ms):.1f}" y="{mt + ph + 14}" text-anchor="middle">{ms}</text>')
        steps = 10 if (1 - ymin) <= 0.5 else 5
        for i in range(steps + 1):
            f = ymin + (1 - ymin) * i / steps
            out.append(f'<line x1="{x0}" y1="{Y(f):.1f}" x2="{x0 + pw}" y2="{Y(f):.1f}" stroke="#eee"/>')
            if k == 0:
                out.append(f'<text x="{x0 - 4}" y="{Y(f) + 4:.1f}" text-anchor="end">{f:.2f}</text>')
        out.append(f'<text x="{x0 + pw / 2}" y="{mt + ph + 30}" text-anchor="middle">budget, ms (log)</text>')
        for s in solvers:
            pts_ = sorted((ms, statistics.mean(v)) for ms, v in series.get((s, n), {}).items())
            if not pts_:
                continue
            d = " ".join(f"{X(ms):.1f},{Y(f):.1f}" for ms, f in pts_)
            dash = f' stroke-dasharray="{dashes[s]}"' if dashes[s] else ""
            out.append(f'<polyline points="{d}" fill="none" stroke="{colours[s]}" stroke-width="2"{dash}/>')
            for ms, f in pts_:
                out.append(f'<circle cx="{X(ms):.1f}" cy="{Y(f):.1f}" r="3" fill="{colours[s]}">'
                           f'<title>{s}, n = {n}, {ms} ms: {f:.3f}</title></circle>')
    out.append(f'<text transform="translate(14,{mt + ph / 2}) rotate(-90)" text-anchor="middle">'
               f'fraction of best known tier-1 value</text>')
    ly = height - 12
    for i, s in enumerate(solvers):
        lx = ml + i * 170
        dash = f' stroke-dasharray="{dashes[s]}"' if dashes[s] else ""
        out.append(f'<line x1="{lx}" y1="{ly - 4}" x2="{lx + 25}" y2="{ly - 4}" stroke="{colours[s]}" '
                   f'stroke-width="2"{dash}/>')
        out.append(f'<text x="{lx + 30}" y="{ly}">{s}</text>')
    out.append(f'<text x="{width - 10}" y="{ly}" text-anchor="end">no solution = 0</text>')
    out.append("</svg>")
    with open(path, "w") as f:
        f.write("\n".join(out) + "\n")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("cmd", choices=["solve", "report"])
    ap.add_argument("files", nargs="*")
    ap.add_argument("--budgets-ms", type=int, nargs="+", default=[1, 10, 100, 1000])
    ap.add_argument("--workers", type=int, nargs="+", default=[1, 2])
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--out", help="solve: write all results as JSON here")
    ap.add_argument("--planner", help="report: the anytime example's --out JSON")
    ap.add_argument("--cpsat", help="report: this script's solve --out JSON")
    ap.add_argument("--known", help="report: planner_cpsat.py solve --out JSON (longer runs)")
    ap.add_argument("--svg", help="report: write the figure here")
    args = ap.parse_args()
    if args.cmd == "report":
        report(args)
        return
    ensure_venv("ortools")
    files = [f for f in args.files if not f.endswith(".planner.json")]
    results = [solve_file(p, args.budgets_ms, args.workers, max(1, args.repeat)) for p in files]
    if args.out:
        with open(args.out, "w") as f:
            json.dump(results, f, indent=1)


if __name__ == "__main__":
    main()
