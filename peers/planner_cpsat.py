#!/usr/bin/env python3
"""B6 peer: the planner's activity-scheduling problem as an OR-Tools CP-SAT model.

Reads a planner `Problem` JSON (planner/src/problem.rs; the B6 instances are written by
`cargo run -p planner --release --example dump_instances`, the simulator's sol problems by
`cargo run -p study --release --example dump_sol_problems`) and builds THE SAME model:

* tasks: every activity is one task, a drive a chain of segment tasks split exactly as
  `Instance::new` splits it (planner/src/instance.rs): boundaries from `split_at_m` or `k` equal
  parts, segment durations and utilities by rounding the cumulative seconds / micro-points at
  each boundary, later segments only bound by the drive's `latest_end_s`, the campaign counted
  on the last segment, a segment's metres = the boundary difference (the same f64 arithmetic);
* timelines: optional intervals (mandatory ones fixed present), start in
  [earliest_start_s, latest_start_s], end <= end_s; one NoOverlap per timeline (`main` and, when
  a task holds it, `hbs_link`; a `main_and_hbs_link` task is in both);
* preconditions: j present => i present and end_i <= start_j (a drive's successors wait for its
  last segment, as in the planner);
* energy: battery at E0 + R (t - start_s) / 3600 minus the energy every task has drawn by t
  (P_i times the part of its run before t), never below 0. The level only falls while some
  task draws, and can only turn up at the end of a task, so it suffices to check the end of
  every task j that can draw more than R together with what may overlap it. A task i on j's
  timeline is either wholly before j (a pairwise order literal) or not yet started; a task on the
  other timeline (link-only against main-only) has drawn min(d_i, max(0, end_j - start_i)): a
  variable ov >= d_i or ov >= end_j - start_i (the solver picks the smaller; ov in [0, d_i]),
  which is exact. Energies are in 1/S W s with S = lcm(16, denominators of every power, of the
  recharge and of E0 x 3600), each input read as the fraction with denominator <= 10^6 nearest
  to it (B6: S = 16, as before; the simulator's sols: whole watts and Wh, S = 16). The test is
  then exact in integers. An input more than 10^-9 (relative) from such a fraction is refused;
  one closer but not equal (a recharge of 40/3 W stored as 13.333333333333334) moves the level
  by at most the `energy_error_wh` the `model` entry of the output reports (the deviations times
  the window and the durations). The planner decides in f64 with a 10^-9 Wh slack, and the
  smallest non-zero level of the integer model is 1/(3600 S) Wh (>= 1.7 x 10^-5 Wh at S = 16),
  so both decide every task the same way while `energy_error_wh` < 10^-9 Wh (the script warns
  on stderr otherwise; for every sol problem and B6 instance it is 0).
  Capacity clipping is NOT modelled: it cannot change the answer when the capacity is at least
  E0 + R x window (no level reaches it: the B6 generator guarantees that) or at least the
  energy of all tasks together (then the clipped level, min(E0 + net(t0, t), min_s C + net(s,
  t)), is >= 0 exactly when E0 + net(t0, t) is, since C + net(s, t) >= C - sum of all draws
  >= 0); anything else is refused;
* left-shifted schedules: the planner starts each task of an order at the earliest second the
  battery allows; CP-SAT places tasks anywhere (at whole seconds, as the planner). On one
  timeline this loses nothing (planner/src/state.rs docs: idling and draining commute up to the
  clipping, so the earliest feasible start dominates). On two timelines the planner's waiting
  rule (wait for a running task of the other timeline to end, then for the recharge) is a rule,
  not a search over waits (its own docs say so), so CP-SAT's optimum is an upper bound of the
  planner's; a higher CP-SAT optimum on a problem with `hbs_link` tasks is that rule, not a
  modelling difference. None has been seen (the sol problems, and 48 + 88 variants with a tight
  battery, zero to 40 W recharge and 15-200 W link tasks: equal optima and equal infeasibility);
* data: produced at a task's end, freed at the end of each downlink (mandatory fixed-time
  main-timeline passes with no data of their own), clipped at 0: D_{k+1} = max(0, D_k + S_k -
  DL_k), and D_k + S_k <= capacity, S_k = data of the tasks between pass k-1 and pass k; volumes
  scaled to integers like the energies (B6 and the sol problems: whole MB, scale 1);
* state-based windows (`driven_window_m`): the metres driven when the task starts are the sum of
  the drive segments before it. With one drive (a chain) the set before a task is a prefix, so
  the planner's f64 sums are the prefix sums, computed here in the same order; the count of
  segments before the task must be one whose prefix lies in [lo - 1e-9, hi + 1e-9] (the
  planner's slack). More than one drive with a state-based window is refused;
* value: utility per tier in micro-points, as the planner: a task's round(points x 10^6), a
  campaign's curve of its member count (instance_checks.rs `campaign_curve`: 0 below
  min_count, round(10^6 x (u + u d + ... + u d^(m-1))) with m = min(n, max_count), the f64
  sum in the same order) through an element constraint; lexicographic, tier 1 first, through one
  weighted objective in units of each tier's grain (gcd of 10^6 and every value a variable term
  can take; the constant part of mandatory tasks is left out) whose weights exceed every
  lower-tier sum. For integer-point utilities (B6) the grain is 10^6: the objective is the
  previous whole-point one, unchanged.

Not supported (the script refuses them): capacity clipping that could bind, state-based
windows with more than one drive or on a drive, downlinks that are optional, movable, produce
data or are off the main timeline, data on a task that does not share the downlinks' timeline,
non-rational inputs (see energy).

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
import math
import os
import statistics
import sys
import time
from fractions import Fraction

from peer_common import ensure_venv


SCALE_T = 16  # base energy scale: units of 1/57600 Wh = 1/16 W*s (B6: exact)
DATA_EPS_MB = 1e-9  # planner/src/state.rs
DISTANCE_EPS_M = 1e-9
DURATION_ROUNDING_S = 1e-6  # planner/src/problem.rs


def as_int(x, what):
    if abs(x - round(x)) > 1e-12:
        raise SystemExit(f"{what} = {x!r} is not an integer: not supported")
    return int(round(x))


def rust_round(x):
    """f64::round: half away from zero (Python's round() is half to even)."""
    a = abs(x)
    r = math.floor(a)
    if a - r >= 0.5:
        r += 1
    return int(r) if x >= 0 else -int(r)


def micro(points):
    return rust_round(points * 1e6)


def scale_for(values, base, what):
    """The least multiple S of `base` making every value x S an integer (each value read as the
    fraction with denominator <= 10^6 nearest to it), and each value's distance from that
    fraction."""
    s, devs = base, []
    for name, v in values:
        f = Fraction(v).limit_denominator(10**6)
        d = abs(float(f) - v)
        if d > 1e-9 * max(1.0, abs(v)):
            raise SystemExit(f"{name} = {v!r} is not a fraction with a small denominator: "
                             f"{what} cannot be scaled to integers exactly")
        devs.append(abs(Fraction(v) - f))
        s = s * f.denominator // math.gcd(s, f.denominator)
    return s, [float(d) for d in devs]


def scaled(v, s):
    return int(Fraction(v).limit_denominator(10**6) * s)


def drive_duration_s(d):
    x = math.ceil(3600.0 * d["length_m"] / d["rate_m_per_h"] - DURATION_ROUNDING_S)
    return int(x) if 0 <= x < 1e12 else 0


def boundaries_m(d):
    if d.get("split_at_m"):
        return [0.0, *d["split_at_m"], d["length_m"]]
    k = drive_duration_s(d) // max(d["min_segment_s"], 1)
    k = min(max(k, 1), max(d.get("max_segments", 4), 1))
    return [d["length_m"] * j / k for j in range(k + 1)]


def campaign_curve(c):
    """planner/src/instance_checks.rs `campaign_curve`: utility_micro[n], n = 0 ..= max_count."""
    out, total, term = [0], 0.0, c["utility"]
    decay, lo = c.get("decay", 1.0), c.get("min_count", 0)
    for n in range(1, c["max_count"] + 1):
        total += term
        term *= decay
        out.append(0 if n < lo else micro(total))
    return out


def split_tasks(p):
    """The planner's tasks (planner/src/instance.rs `Instance::new`), as dicts."""
    acts = p["activities"]
    ids = {a["id"]: i for i, a in enumerate(acts)}
    camp = {c["id"]: k for k, c in enumerate(p.get("campaigns", []))}
    counts = []
    for a in acts:
        counts.append(1 if a["kind"]["type"] == "task" else len(boundaries_m(a["kind"])) - 1)
    first = [sum(counts[:i]) for i in range(len(acts))]
    last = [first[i] + counts[i] - 1 for i in range(len(acts))]
    tasks = []
    for ai, a in enumerate(acts):
        kind = a["kind"]
        dur = kind["duration_s"] if kind["type"] == "task" else drive_duration_s(kind)
        base = {
            "name": a["id"], "activity": ai, "drive": None, "dur": int(dur),
            "es": int(a["earliest_start_s"]), "ls": int(a["latest_start_s"]),
            "power": a["power_w"], "data": a.get("data_mb", 0.0),
            "down": a.get("downlink_mb", 0.0),
            "pre": [last[ids[q]] for q in a.get("preconditions", [])],
            "mand": bool(a.get("mandatory", False)), "tier": int(a.get("tier", 1)) - 1,
            "util": micro(a.get("utility", 0.0)),
            "campaign": camp[a["campaign"]] if a.get("campaign") is not None else None,
            "drive_m": 0.0, "window": a.get("driven_window_m"),
            "timeline": a.get("timeline", "main"),
        }
        if kind["type"] == "task":
            tasks.append(base)
            continue
        b = boundaries_m(kind)
        k = len(b) - 1
        total_s, total_u, length = float(dur), float(base["util"]), kind["length_m"]
        at_s = lambda m: rust_round(total_s * m / length)
        at_u = lambda m: rust_round(total_u * m / length)
        end_by = min(kind.get("latest_end_s") or p["end_s"], p["end_s"])
        for j in range(k):
            t = dict(base)
            t["name"] = f"{a['id']}#{j + 1}/{k}"
            t["drive"] = ai
            t["dur"] = max(at_s(b[j + 1]) - at_s(b[j]), 1)
            t["util"] = at_u(b[j + 1]) - at_u(b[j])
            frac = (b[j + 1] - b[j]) / length
            t["data"] = base["data"] * frac
            t["down"] = base["down"] * frac
            t["drive_m"] = b[j + 1] - b[j]
            if j > 0:
                t["pre"] = [first[ai] + j - 1]
                t["ls"] = max(end_by - t["dur"], base["es"])
                t["window"] = None
            else:
                t["ls"] = max(min(t["ls"], end_by - t["dur"]), base["es"])
            if j + 1 < k:
                t["campaign"] = None
            tasks.append(t)
    return tasks


def uses_main(tl):
    return tl != "hbs_link"


def uses_link(tl):
    return tl != "main"


def shares(a, b):
    return (uses_main(a) and uses_main(b)) or (uses_link(a) and uses_link(b))


def build(problem):
    from ortools.sat.python import cp_model

    p = problem
    t0, t1 = p["start_s"], p["end_s"]
    tasks = split_tasks(p)
    campaigns = p.get("campaigns", [])
    n = len(tasks)
    dur = [t["dur"] for t in tasks]
    es = [max(t["es"], t0) for t in tasks]
    ls = [min(t["ls"], t1 - t["dur"]) for t in tasks]
    mand = [t["mand"] for t in tasks]
    tl = [t["timeline"] for t in tasks]
    tier = [t["tier"] + 1 for t in tasks]
    util = [t["util"] for t in tasks]

    # Energy in 1/S W s.
    S, e_devs = scale_for([("recharge_w", p["recharge_w"]),
                          ("initial_energy_wh x 3600", p["initial_energy_wh"] * 3600)]
                         + [(f"{t['name']}.power_w", t["power"]) for t in tasks],
                         SCALE_T, "energies")
    # Worst-case drift of a level between the f64 inputs and the fractions taken for them.
    energy_error_wh = (e_devs[0] * (t1 - t0) + e_devs[1]
                       + sum(d * t["dur"] for d, t in zip(e_devs[2:], tasks))) / 3600
    if energy_error_wh >= 1e-9:
        print(f"warning: energies deviate up to {energy_error_wh:.3g} Wh from the fractions "
              "modelled: a battery tie could be decided unlike the planner", file=sys.stderr)
    RS = scaled(p["recharge_w"], S)
    E0 = scaled(p["initial_energy_wh"] * 3600, S)
    power = [scaled(t["power"], S) for t in tasks]  # W x S
    cap_needed = p["initial_energy_wh"] + p["recharge_w"] * (t1 - t0) / 3600
    all_draws_wh = sum(t["power"] * t["dur"] for t in tasks) / 3600
    if p["battery_capacity_wh"] < cap_needed and p["battery_capacity_wh"] < all_draws_wh:
        raise SystemExit("battery capacity could clip and bind: not modelled")
    # Data in 1/SD MB.
    SD, d_devs = scale_for([("initial_data_mb", p.get("initial_data_mb", 0.0))]
                          + [(f"{t['name']}.data_mb", t["data"]) for t in tasks]
                          + [(f"{t['name']}.downlink_mb", t["down"]) for t in tasks],
                          1, "data volumes")
    data = [scaled(t["data"], SD) for t in tasks]
    down = [scaled(t["down"], SD) for t in tasks]
    data_cap = math.floor((p["data_capacity_mb"] + DATA_EPS_MB) * SD)
    d_init = scaled(p.get("initial_data_mb", 0.0), SD)

    m = cp_model.CpModel()
    pres, start, end, itv = [], [], [], []
    for i in range(n):
        if ls[i] < es[i]:
            if mand[i]:
                raise SystemExit(f"mandatory {tasks[i]['name']} cannot fit")
            pres.append(m.new_constant(0))
        else:
            pres.append(m.new_constant(1) if mand[i] else m.new_bool_var(f"x{i}"))
        lo, hi = es[i], max(es[i], ls[i])
        s = m.new_int_var(lo, hi, f"s{i}")
        e = m.new_int_var(lo + dur[i], hi + dur[i], f"e{i}")
        start.append(s)
        end.append(e)
        itv.append(m.new_optional_interval_var(s, dur[i], e, pres[i], f"I{i}"))
    m.add_no_overlap([itv[i] for i in range(n) if uses_main(tl[i])])
    link = [itv[i] for i in range(n) if uses_link(tl[i])]
    if link:
        m.add_no_overlap(link)

    # Preconditions.
    must_before = set()
    for j, t in enumerate(tasks):
        for i in t["pre"]:
            m.add_implication(pres[j], pres[i])
            m.add(end[i] <= start[j]).only_enforce_if(pres[j])
            must_before.add((i, j))

    # Pairwise order literals on a shared timeline: before[i, j] <=> both present, i first.
    both = {}
    before = {}
    for i in range(n):
        for j in range(i + 1, n):
            if not shares(tl[i], tl[j]):
                continue
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

    # Energy at the end of every task that can drain the battery (with what may overlap it).
    cost = [power[i] * dur[i] for i in range(n)]
    for j in range(n):
        cross = [i for i in range(n) if i != j and not shares(tl[i], tl[j])]
        if power[j] + max((power[i] for i in cross), default=0) <= RS:
            continue
        terms = [cost[i] * before[i, j] for i in range(n) if (i, j) in before]
        for i in cross:
            if power[i] == 0 or es[i] >= ls[j] + dur[j]:
                continue  # never draws before j ends
            if ls[i] + dur[i] <= es[j] + dur[j] or (i, j) in must_before:
                terms.append(cost[i] * pres[i])  # wholly before j's end
                continue
            ov = m.new_int_var(0, dur[i], f"ov{i}_{j}")
            f = m.new_bool_var(f"f{i}_{j}")
            m.add(ov >= dur[i]).only_enforce_if(f)
            m.add(ov >= end[j] - start[i]).only_enforce_if([f.negated(), pres[i]])
            terms.append(power[i] * ov)
        m.add(E0 + RS * (end[j] - t0) - cost[j] - sum(terms) >= 0).only_enforce_if(pres[j])

    # Data between downlinks.
    comms = [i for i in range(n) if down[i] > 0]
    for c in comms:
        if not mand[c] or es[c] != ls[c] or data[c] != 0 or tl[c] != "main":
            raise SystemExit(f"{tasks[c]['name']}: downlinks must be mandatory, fixed, "
                             "data-free, on the main timeline")
    comms.sort(key=lambda c: es[c])
    others = [i for i in range(n) if down[i] == 0]
    if comms and any(data[i] and not uses_main(tl[i]) for i in others):
        raise SystemExit("data on a task off the main timeline: not supported")
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
    big = max(10**7, data_cap + sum(data) + sum(down) + 1)  # 10**7: the B6 model as before
    for k, c in enumerate(comms):
        seg = cum[k] - prev
        m.add(level + seg <= data_cap)
        nxt = m.new_int_var(0, data_cap, f"D{k + 1}")
        diff = m.new_int_var(-big, big, f"diff{k + 1}")
        m.add(diff == level + seg - down[c])
        m.add_max_equality(nxt, [diff, 0])
        level, prev = nxt, cum[k]
    m.add(level + total_data - prev <= data_cap)

    # State-based windows: the segments of the one drive before the task.
    windowed = [j for j in range(n) if tasks[j]["window"] is not None]
    if windowed:
        from ortools.sat.python.cp_model import Domain

        drives = {t["drive"] for t in tasks if t["drive"] is not None}
        if len(drives) > 1:
            raise SystemExit("state-based windows with more than one drive: not supported")
        segs = [i for i in range(n) if tasks[i]["drive"] is not None]
        prefix = [0.0]
        for i in segs:
            prefix.append(prefix[-1] + tasks[i]["drive_m"])
        for j in windowed:
            if tasks[j]["drive"] is not None or any(not shares(tl[s], tl[j]) for s in segs):
                raise SystemExit(f"{tasks[j]['name']}: a state-based window on a drive or off "
                                 "the drive's timeline: not supported")
            lo, hi = tasks[j]["window"]
            ok = [k for k, d in enumerate(prefix)
                  if lo - DISTANCE_EPS_M <= d <= hi + DISTANCE_EPS_M]
            cnt = sum(before[s, j] for s in segs if (s, j) in before)
            m.add_linear_expression_in_domain(cnt, Domain.from_values(ok)).only_enforce_if(
                pres[j])

    # Campaign utilities: the curve of the member count.
    camp_util = []  # (tier, IntVar or int, values)
    for k, c in enumerate(campaigns):
        curve = campaign_curve(c)
        members = [i for i in range(n) if tasks[i]["campaign"] == k]
        values = [curve[min(x, c["max_count"])] for x in range(len(members) + 1)]
        count = sum(pres[i] for i in members)
        u = m.new_int_var(0, max(values), f"u{k}")
        cnt = m.new_int_var(0, len(members), f"n{k}")
        m.add(cnt == count)
        m.add_element(cnt, values, u)
        camp_util.append((int(c.get("tier", 1)), u, values))

    # Lexicographic tiers through one weighted sum, in units of each tier's grain.
    var_terms = {}  # tier -> [(coef_micro, var)]
    for i in range(n):
        if util[i] and not (mand[i] and ls[i] >= es[i]):
            var_terms.setdefault(tier[i], []).append((util[i], pres[i]))
    for t, u, values in camp_util:
        if max(values):
            var_terms.setdefault(t, []).append((1, u, values))
    tiers = sorted(set(tier) | set(var_terms))
    weight, w = {}, 1
    for t in reversed(tiers):
        g = 1_000_000
        top = 0
        for term in var_terms.get(t, []):
            if len(term) == 2:
                g = math.gcd(g, term[0])
            else:
                for v in term[2]:
                    g = math.gcd(g, v)
        for term in var_terms.get(t, []):
            top += term[0] // g if len(term) == 2 else max(term[2]) // g
        weight[t] = (w, g)
        w *= top + 1
    # Campaign terms are in micro-points: divide through the grain with a scaled variable.
    obj = 0
    for t, terms in var_terms.items():
        wt, g = weight[t]
        for term in terms:
            if len(term) == 2:
                obj += wt * (term[0] // g) * term[1]
            else:
                ug = m.new_int_var(0, max(term[2]) // g, "ug")
                m.add(ug * g == term[1])
                obj += wt * ug
    m.maximize(obj)
    info = {"energy_scale": S, "data_scale": SD, "energy_error_wh": energy_error_wh,
            "data_error_mb": sum(d_devs), "tasks": n}
    return m, pres, start, tasks, camp_util, info


def solve(path, workers, time_limit):
    from ortools.sat.python import cp_model

    clock = time.perf_counter()
    with open(path) as f:
        problem = json.load(f)
    m, pres, start, tasks, camp_util, info = build(problem)
    solver = cp_model.CpSolver()
    solver.parameters.num_workers = workers
    solver.parameters.max_time_in_seconds = time_limit
    status = solver.solve(m)
    wall = time.perf_counter() - clock
    name = solver.status_name(status)
    value = [0, 0, 0, 0]
    plan = []
    if status in (cp_model.OPTIMAL, cp_model.FEASIBLE):
        for i, t in enumerate(tasks):
            if solver.boolean_value(pres[i]):
                value[t["tier"]] += t["util"]
                plan.append((solver.value(start[i]), t["name"]))
        for t, u, _ in camp_util:
            value[t - 1] += solver.value(u)
    return {
        "status": name,
        "value_micro": value,
        "bound": solver.best_objective_bound,
        "objective": solver.objective_value,
        "wall_ms": wall * 1e3,
        "solver_wall_ms": solver.wall_time * 1e3,
        "plan": sorted(plan),
        "model": info,
    }


def is_problem(path):
    """Whether `path` holds a planner `Problem` (a directory's index or results do not)."""
    try:
        with open(path) as f:
            p = json.load(f)
    except (OSError, ValueError):
        return False
    return isinstance(p, dict) and "activities" in p


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
        if not is_problem(path):
            print(f"{path}: not a planner Problem (no activities): skipped", file=sys.stderr)
            continue
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
                "model": r["model"],
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
