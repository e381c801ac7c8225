#!/usr/bin/env python3
"""B6 peer: the planner's activity-scheduling problem as an OR-Tools CP-SAT model.

Reads a planner `Problem` JSON (planner/src/problem.rs; the B6 instances are written by
`cargo run -p planner --release --example dump_instances`) and builds THE SAME model:

* one activity at a time: optional intervals (mandatory ones fixed present) + NoOverlap, start
  in [earliest_start_s, latest_start_s] and >= start_s, end <= end_s;
* preconditions: j present => i present and end_i <= start_j;
* energy: battery at E0 + R (t - start_s) / 3600 - sum of P_i d_i / 3600 over the tasks ended
  by t, never below 0. The level only falls during a task drawing more than R, so it suffices
  to check the end of each such task j: E0 + R (end_j - t0)/3600 - P_j d_j/3600
  - sum_i P_i d_i/3600 [i before j] >= 0, with pairwise order literals. Everything is
  multiplied by 57 600 = 3600 x 16, so it is exact for the quantised B6 instances (R and E0
  multiples of 1/16). Capacity clipping is NOT modelled: the script checks that the capacity is
  at least E0 + R x window, so it cannot bind (the B6 generator guarantees that);
* data: produced at an activity's end, freed at the end of each downlink (mandatory fixed-time
  comm passes with no data of their own), clipped at 0: D_{k+1} = max(0, D_k + S_k - DL_k),
  and D_k + S_k <= capacity, S_k = data of the tasks between pass k-1 and pass k;
* value: integer utility points per tier (the planner's micro-points / 10^6), lexicographic,
  tier 1 first, through one weighted objective whose weights exceed every lower-tier sum.

Not supported (the script refuses them): drives (segments), campaigns, driven windows,
non-integer utilities or powers, downlinks that are optional, movable or produce data.

Usage:
  planner_cpsat.py solve FILE.json... [--workers 1 2] [--time-limit 60] [--repeat 3] [--out F]
prints one JSON line per (file, workers): status, value per tier in micro-points, wall ms
(median of --repeat solves, model building included), and checks it against
FILE.planner.json when present (exit 1 if two proven optima differ).
  planner_cpsat.py report --peers F --criterion DIR
prints the markdown table of BENCHMARKS.md from those results and criterion's estimates of
`cargo bench --bench planner`.
"""
import argparse
import json
import os
import statistics
import sys
import time

from peer_common import ensure_venv



SCALE_T = 16  # energy scale: units of 1/57600 Wh = 1/16 W*s


def as_int(x, what):
    if abs(x - round(x)) > 1e-12:
        raise SystemExit(f"{what} = {x!r} is not an integer: not supported")
    return int(round(x))


def build(problem):
    from ortools.sat.python import cp_model

    p = problem
    t0, t1 = p["start_s"], p["end_s"]
    acts = p["activities"]
    if p.get("campaigns"):
        raise SystemExit("campaigns are not supported")
    n = len(acts)
    ids = {a["id"]: i for i, a in enumerate(acts)}
    dur, es, ls, power, data, down, mand, tier, util = [], [], [], [], [], [], [], [], []
    for a in acts:
        kind = a["kind"]
        if kind.get("type") != "task":
            raise SystemExit(f"{a['id']}: only plain tasks are supported (no drives)")
        if a.get("driven_window_m") is not None or a.get("campaign") is not None:
            raise SystemExit(f"{a['id']}: driven windows / campaigns not supported")
        dur.append(int(kind["duration_s"]))
        es.append(max(int(a["earliest_start_s"]), t0))
        ls.append(min(int(a["latest_start_s"]), t1 - int(kind["duration_s"])))
        power.append(as_int(a["power_w"], f"{a['id']}.power_w"))
        data.append(as_int(a.get("data_mb", 0.0), f"{a['id']}.data_mb"))
        down.append(as_int(a.get("downlink_mb", 0.0), f"{a['id']}.downlink_mb"))
        mand.append(bool(a.get("mandatory", False)))
        tier.append(int(a.get("tier", 1)))
        util.append(as_int(a.get("utility", 0.0), f"{a['id']}.utility"))
    R16 = as_int(p["recharge_w"] * SCALE_T, "recharge_w x 16")
    E0 = as_int(p["initial_energy_wh"] * 3600 * SCALE_T, "initial_energy_wh x 57600")
    cap_needed = p["initial_energy_wh"] + p["recharge_w"] * (t1 - t0) / 3600
    if p["battery_capacity_wh"] < cap_needed:
        raise SystemExit("battery capacity could clip: not modelled (use planner::b6_problem)")
    data_cap = as_int(p["data_capacity_mb"], "data_capacity_mb")
    d_init = as_int(p.get("initial_data_mb", 0.0), "initial_data_mb")

    m = cp_model.CpModel()
    pres, start, end, itv = [], [], [], []
    for i in range(n):
        if ls[i] < es[i]:
            if mand[i]:
                raise SystemExit(f"mandatory {acts[i]['id']} cannot fit")
            pres.append(m.new_constant(0))
        else:
            pres.append(m.new_constant(1) if mand[i] else m.new_bool_var(f"x{i}"))
        lo, hi = es[i], max(es[i], ls[i])
        s = m.new_int_var(lo, hi, f"s{i}")
        e = m.new_int_var(lo + dur[i], hi + dur[i], f"e{i}")
        start.append(s)
        end.append(e)
        itv.append(m.new_optional_interval_var(s, dur[i], e, pres[i], f"I{i}"))
    m.add_no_overlap(itv)

    # Preconditions.
    must_before = set()
    for j, a in enumerate(acts):
        for q in a.get("preconditions", []):
            i = ids[q]
            m.add_implication(pres[j], pres[i])
            m.add(end[i] <= start[j]).only_enforce_if(pres[j])
            must_before.add((i, j))

    # Pairwise order literals: before[i][j] <=> i and j present and i runs first.
    both = {}
    before = {}
    for i in range(n):
        for j in range(i + 1, n):
            ij_ok = es[i] + dur[i] <= ls[j] and (j, i) not in must_before
            ji_ok = es[j] + dur[j] <= ls[i] and (i, j) not in must_before
            if not ij_ok and not ji_ok:
                m.add_bool_or([pres[i].negated(), pres[j].negated()])
                continue
            b = m.new_bool_var(f"both{i}_{j}")
            m.add_implication(b, pres[i])
            m.add_implication(b, pres[j])
            m.add_bool_or([pres[i].negated(), pres[j].negated(), b])
            both[i, j] = b
            if ij_ok and ji_ok:
                o = m.new_bool_var(f"o{i}_{j}")  # i first
                m.add(end[i] <= start[j]).only_enforce_if([b, o])
                m.add(end[j] <= start[i]).only_enforce_if([b, o.negated()])
                bij = m.new_bool_var(f"b{i}_{j}")
                bji = m.new_bool_var(f"b{j}_{i}")
                m.add_bool_and([b, o]).only_enforce_if(bij)
                m.add_bool_or([b.negated(), o.negated(), bij])
                m.add_bool_and([b, o.negated()]).only_enforce_if(bji)
                m.add_bool_or([b.negated(), o, bji])
                before[i, j], before[j, i] = bij, bji
            elif ij_ok:
                before[i, j] = b
            else:
                before[j, i] = b

    # Energy at the end of every task that drains the battery.
    cost = [power[i] * dur[i] * SCALE_T for i in range(n)]
    for j in range(n):
        if power[j] * SCALE_T <= R16:
            continue
        terms = [cost[i] * before[i, j] for i in range(n) if (i, j) in before]
        m.add(E0 + R16 * (end[j] - t0) - cost[j] - sum(terms) >= 0).only_enforce_if(pres[j])

    # Data between downlinks.
    comms = [i for i in range(n) if down[i] > 0]
    for c in comms:
        if not mand[c] or es[c] != ls[c] or data[c] != 0:
            raise SystemExit(f"{acts[c]['id']}: downlinks must be mandatory, fixed, data-free")
    comms.sort(key=lambda c: es[c])
    others = [i for i in range(n) if down[i] == 0]
    total_data = sum(data[i] * pres[i] for i in others)
    cum = []  # data produced before comm k
    for c in comms:
        terms = []
        for i in others:
            if data[i] == 0:
                continue
            if es[i] + dur[i] > es[c]:  # cannot end before the pass
                continue
            if ls[i] < es[c] + dur[c]:  # cannot start after it
                terms.append(data[i] * pres[i])
                continue
            a = m.new_bool_var(f"a{i}_{c}")
            m.add_implication(a, pres[i])
            m.add(end[i] <= es[c]).only_enforce_if(a)
            m.add(start[i] >= es[c] + dur[c]).only_enforce_if([pres[i], a.negated()])
            terms.append(data[i] * a)
        cum.append(sum(terms))
    level = d_init
    prev = 0
    for k, c in enumerate(comms):
        seg = cum[k] - prev
        m.add(level + seg <= data_cap)
        nxt = m.new_int_var(0, data_cap, f"D{k + 1}")
        diff = m.new_int_var(-10**7, 10**7, f"diff{k + 1}")
        m.add(diff == level + seg - down[c])
        m.add_max_equality(nxt, [diff, 0])
        level, prev = nxt, cum[k]
    m.add(level + total_data - prev <= data_cap)

    # Lexicographic tiers through one weighted sum.
    tiers = sorted(set(tier))
    weight, w = {}, 1
    for t in reversed(tiers):
        weight[t] = w
        w *= sum(util[i] for i in range(n) if tier[i] == t) + 1
    m.maximize(sum(weight[tier[i]] * util[i] * pres[i] for i in range(n) if util[i]))
    return m, pres, start, tier, util


def solve(path, workers, time_limit):
    from ortools.sat.python import cp_model

    clock = time.perf_counter()
    with open(path) as f:
        problem = json.load(f)
    m, pres, start, tier, util = build(problem)
    solver = cp_model.CpSolver()
    solver.parameters.num_workers = workers
    solver.parameters.max_time_in_seconds = time_limit
    status = solver.solve(m)
    wall = time.perf_counter() - clock
    name = solver.status_name(status)
    value = [0, 0, 0, 0]
    plan = []
    if status in (cp_model.OPTIMAL, cp_model.FEASIBLE):
        for i in range(len(pres)):
            if solver.boolean_value(pres[i]):
                value[tier[i] - 1] += util[i] * 1_000_000
                plan.append((solver.value(start[i]), problem["activities"][i]["id"]))
    return {
        "status": name,
        "value_micro": value,
        "bound": solver.best_objective_bound,
        "objective": solver.objective_value,
        "wall_ms": wall * 1e3,
        "solver_wall_ms": solver.wall_time * 1e3,
        "plan": sorted(plan),
    }


def criterion_ms(root, bench, param):
    path = os.path.join(root, "planner_b6", bench, str(param), "new", "estimates.json")
    with open(path) as f:
        est = json.load(f)
    return est["median"]["point_estimate"] / 1e6


def report(peers_path, criterion_root):
    with open(peers_path) as f:
        peers = json.load(f)
    by = {(r["file"], r["workers"]): r for r in peers}
    files = sorted({r["file"] for r in peers}, key=lambda s: (int(s.split("_")[0][1:]), s))
    print("| instance | planner: proven optimum, ms | CP-SAT 1 worker, ms (status) "
          "| CP-SAT 2 workers, ms (status) | objective tier 1 / tier 2, equal? | ours / CP-SAT 1w |")
    print("|---|---|---|---|---|---|")
    for name in files:
        stem = name[: -len(".json")]
        n, seed = stem.split("_")
        ours = criterion_ms(criterion_root, f"prove_{n}", seed[len("seed"):])
        r1, r2 = by.get((name, 1)), by.get((name, 2))
        cell = lambda r: (f"{r['wall_ms_median']:.1f} [{r['wall_ms_min']:.1f}–{r['wall_ms_max']:.1f}] "
                          f"({'/'.join(sorted(set(r['status'])))})") if r else "–"
        v = r1["value_micro"]
        eq = "yes" if r1.get("equal") else "NO"
        print(f"| {stem} | {ours:.1f} | {cell(r1)} | {cell(r2)} | "
              f"{v[0] / 1e6:g} / {v[1] / 1e6:g}, {eq} | {ours / r1['wall_ms_median']:.2f} |")
    for seed in (1, 2, 3):
        try:
            ms = criterion_ms(criterion_root, "anytime_10ms_n80", seed)
            print(f"anytime_10ms_n80 seed{seed}: {ms:.2f} ms per call (criterion median)")
        except OSError:
            pass


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("cmd", choices=["solve", "report"])
    ap.add_argument("files", nargs="*")
    ap.add_argument("--peers")
    ap.add_argument("--criterion")
    ap.add_argument("--workers", type=int, nargs="+", default=[1, 2])
    ap.add_argument("--time-limit", type=float, default=60.0)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--out", help="write all results as a JSON list here")
    args = ap.parse_args()
    if args.cmd == "report":
        report(args.peers, args.criterion)
        return
    ensure_venv("ortools")
    results = []
    bad = 0
    for path in [f for f in args.files if not f.endswith(".planner.json")]:
        planner = None
        ppath = path[: -len(".json")] + ".planner.json"
        if os.path.exists(ppath):
            with open(ppath) as f:
                planner = json.load(f)
        for w in args.workers:
            runs = [solve(path, w, args.time_limit) for _ in range(max(1, args.repeat))]
            r = runs[-1]
            times = [x["wall_ms"] for x in runs]
            out = {
                "file": os.path.basename(path),
                "workers": w,
                "status": [x["status"] for x in runs],
                "value_micro": r["value_micro"],
                "wall_ms_median": statistics.median(times),
                "wall_ms_min": min(times),
                "wall_ms_max": max(times),
                "solver_wall_ms_median": statistics.median(x["solver_wall_ms"] for x in runs),
            }
            if planner is not None:
                both_opt = r["status"] == "OPTIMAL" and planner["status"] == "Optimal"
                equal = planner["value_micro"] == r["value_micro"]
                out["planner_status"] = planner["status"]
                out["planner_value_micro"] = planner["value_micro"]
                out["equal"] = equal
                if both_opt and not equal:
                    bad += 1
                    out["MISMATCH"] = True
            print(json.dumps(out), flush=True)
            results.append(out)
    if args.out:
        with open(args.out, "w") as f:
            json.dump(results, f, indent=1)
    if bad:
        print(f"{bad} proven optima differ", file=sys.stderr)
        sys.exit(1)


if __name__ == "__main__":
    main()
