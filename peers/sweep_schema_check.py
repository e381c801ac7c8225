#!/usr/bin/env python3
"""Independent reader for a `solsim sweep` directory: pyarrow and numpy, not solsim's Rust.

    python3 peers/sweep_schema_check.py SWEEP_DIR [--schema tests/sweep_schema.json]

Reads SWEEP_DIR/runs.parquet and sols.parquet with pyarrow and checks, against the documented
schema (tests/sweep_schema.json, described in docs/sweep-schema.md) and the directory's own
manifest.json and summary.json:

    columns     names in order, arrow types ("uint64", "string", "double", "bool", …) and
                nullability exactly as documented
    rows        runs.parquet: one row per run index of the manifest's range × strategy, in
                run order then the manifest's strategy order, one run_seed per run index;
                sols.parquet: every (run_index, strategy) of runs.parquet the same number of
                times (the calendar's sols, the same sols for each, ascending) and no other
    nulls       each nullable column null exactly when documented (skip_reason when the rover
                drove, fault_after_m when fault is, onboard_error_m unless applied, …)
    tables      each run's totals equal its sols' (distance, drive sols, faults by kind, onboard
                localizations applied and rejected, ground localizations, sols with the truth
                outside the disc, largest truth error, goal reached)
    metadata    the key-value metadata (solsim.format, solsim.seed, solsim.scenario_sha256, …)
                of both files equal to manifest.json
    manifest    complete, of the documented format, SHA-256 of every listed file
    summary     the manifest's scenario, seed, runs, shard, segment and strategies; per strategy
                each rate's count (e.g. no_path_rate: runs with no_path_faults > 0) and runs,
                each figure's n, mean, median, p5 and p95 (numpy.quantile, linear); per paired
                difference its number of pairs and mean — floats to 1e-9 relative

Prints one line on stdout and exits 0 when everything agrees; otherwise prints every
difference on stderr, one per line, and exits 1 (2 for unusable arguments or files).

Needs pyarrow and numpy: `ensure_venv` (peer_common.py) creates peers/.venv when needed,
installs peers/requirements.txt there and re-runs itself with that interpreter.
tests/sweep_parquet_pyarrow.rs runs it on fresh sweeps.
"""

import argparse
import hashlib
import json
import sys
from pathlib import Path

from peer_common import PEERS, ensure_venv

TABLES = ("runs.parquet", "sols.parquet")
REL_TOL = 1e-9

# summary.json rate name -> (runs.parquet column, predicate on its numpy values)
RATES = {
    "no_path_rate": ("no_path_faults", lambda v: v > 0),
    "fault_rate": ("faults", lambda v: v > 0),
    "truth_outside_disc_rate": ("truth_outside_disc_sols", lambda v: v > 0),
    "goal_reached_rate": ("goal_reached", lambda v: v),
}


class Problems:
    """Differences found, each one line naming the file and what differs."""

    def __init__(self):
        self.lines = []

    def add(self, where, message):
        self.lines.append(f"{where}: {message}")

    def equal(self, where, what, got, expected):
        if got != expected:
            self.add(where, f"{what}: expected {expected!r}, got {got!r}")

    def close(self, where, what, got, expected, scale):
        """`got` equals `expected` to REL_TOL relative to `scale` (the data's magnitude)."""
        if got is None or expected is None:
            self.equal(where, what, got, expected)
        elif abs(got - expected) > REL_TOL * max(abs(expected), abs(got), scale, 1e-300):
            self.add(where, f"{what}: expected {expected!r} (recomputed), got {got!r}")


def fail_usage(message):
    print(f"sweep_schema_check: {message}", file=sys.stderr)
    sys.exit(2)


def load_json(path):
    try:
        return json.loads(path.read_text())
    except (OSError, ValueError) as e:
        fail_usage(f"{path}: cannot read JSON: {e}")


def check_columns(problems, name, schema, documented):
    """Returns whether the columns are as documented."""
    where = name
    before = len(problems.lines)
    got = [(f.name, str(f.type), f.nullable) for f in schema]
    want = [(c["name"], c["type"], c["nullable"]) for c in documented]
    got_names, want_names = [g[0] for g in got], [w[0] for w in want]
    if got_names != want_names:
        problems.add(where, f"columns: expected {want_names}, got {got_names}")
    for (g_name, g_type, g_null), (w_name, w_type, w_null) in zip(got, want):
        if g_name != w_name:
            continue
        if g_type != w_type:
            problems.add(where, f"column {g_name!r}: type: expected {w_type}, got {g_type}")
        if g_null != w_null:
            problems.add(where, f"column {g_name!r}: nullable: expected {w_null}, got {g_null}")
    return len(problems.lines) == before


def expected_metadata(manifest):
    kv = {
        "solsim.format": manifest["format"],
        "solsim.version": manifest["solsim_version"],
        "solsim.scenario": manifest["scenario"]["name"],
        "solsim.scenario_sha256": manifest["scenario"]["sha256"],
        "solsim.seed": str(manifest["seed"]),
        "solsim.runs": str(manifest["runs"]),
        "solsim.strategies": ",".join(manifest["strategies"]),
    }
    shard = manifest.get("shard")
    if shard is not None:
        kv["solsim.shard"] = (f"{shard['index']}/{shard['count']} "
                              f"(runs {shard['first_run']}..{shard['end_run']})")
    return kv


def check_metadata(problems, name, metadata, manifest):
    got = {k.decode(): v.decode() for k, v in (metadata or {}).items()
           if not k.startswith(b"ARROW:")}
    want = expected_metadata(manifest)
    for key in sorted(set(got) | set(want)):
        if key not in got:
            problems.add(name, f"key-value metadata {key!r}: missing (manifest.json: "
                               f"{want[key]!r})")
        elif key not in want:
            problems.add(name, f"key-value metadata {key!r}: not documented "
                               f"(value {got[key]!r})")
        elif got[key] != want[key]:
            problems.add(name, f"key-value metadata {key!r}: {got[key]!r}, but manifest.json "
                               f"says {want[key]!r}")


def check_manifest(problems, sweep_dir, manifest, schema_doc):
    where = "manifest.json"
    problems.equal(where, "format", manifest.get("format"), schema_doc["format"])
    problems.equal(where, "state", manifest.get("state"), "complete")
    files = manifest.get("files", {})
    problems.equal(where, "files", sorted(files), sorted([*TABLES, "summary.json"]))
    for name, sha in sorted(files.items()):
        got = hashlib.sha256((sweep_dir / name).read_bytes()).hexdigest()
        if got != sha:
            problems.add(where, f"files.{name}: lists SHA-256 {sha}, the file's is {got}")


def run_range(manifest):
    shard = manifest.get("shard")
    if shard is None:
        return range(manifest["runs"])
    return range(shard["first_run"], shard["end_run"])


def check_rows(problems, runs, sols, manifest):
    import pyarrow as pa
    import pyarrow.compute as pc

    strategies = manifest["strategies"]
    run_index = runs.column("run_index").to_pylist()
    strategy = runs.column("strategy").to_pylist()
    want_keys = [(i, s) for i in run_range(manifest) for s in strategies]
    got_keys = list(zip(run_index, strategy))
    if got_keys != want_keys:
        first = next((k for k, (g, w) in enumerate(zip(got_keys, want_keys)) if g != w),
                     min(len(got_keys), len(want_keys)))
        problems.add("runs.parquet", f"rows: expected {len(want_keys)} rows (run indices "
                                     f"{run_range(manifest)} × strategies {strategies}, in that "
                                     f"order), got {len(got_keys)}; first difference at row "
                                     f"{first}")
    seeds = {}
    for (i, s), seed in zip(got_keys, runs.column("run_seed").to_pylist()):
        if seeds.setdefault(i, seed) != seed:
            problems.add("runs.parquet", f"run_seed: run {i} has {seeds[i]} and {seed} "
                                         f"({s}); every strategy of a run shares its seed")

    # sols.parquet: the calendar of each (run_index, strategy), in table order.
    calendars = {}
    sol_keys = zip(sols.column("run_index").to_pylist(), sols.column("strategy").to_pylist(),
                   sols.column("sol").to_pylist())
    order = []
    for i, s, sol in sol_keys:
        if (i, s) not in calendars:
            calendars[(i, s)] = []
            order.append((i, s))
        calendars[(i, s)].append(sol)
    if order != got_keys:
        problems.add("sols.parquet", f"(run_index, strategy) groups: expected those of "
                                     f"runs.parquet in its order ({len(got_keys)}), got "
                                     f"{len(order)} groups")
    lengths = sorted({len(c) for c in calendars.values()})
    if len(lengths) > 1:
        problems.add("sols.parquet", f"sols per (run_index, strategy): expected the same "
                                     f"number for all, got {lengths}")
    elif lengths and sols.num_rows != runs.num_rows * lengths[0]:
        problems.add("sols.parquet", f"rows: expected {runs.num_rows} × {lengths[0]}, got "
                                     f"{sols.num_rows}")
    distinct = {tuple(c) for c in calendars.values()}
    if len(distinct) > 1:
        problems.add("sols.parquet", f"sol numbers: expected the same calendar for every "
                                     f"(run_index, strategy), got {len(distinct)} different")
    for c in distinct:
        if list(c) != sorted(c):
            problems.add("sols.parquet", f"sol numbers: expected ascending, got {list(c)}")

    # Each run's totals from its sols, aggregated by pyarrow.
    fault = pc.fill_null(sols.column("fault"), "")
    applied = sols.column("onboard_applied")
    per_sol = pa.table({
        "run_index": sols.column("run_index"),
        "strategy": sols.column("strategy"),
        "distance_m": sols.column("distance_m"),
        "drive_time_s": sols.column("drive_time_s"),
        "drive_sols": sols.column("drove"),
        "no_path_faults": pc.equal(fault, "NO_PATH"),
        "keep_out_faults": pc.equal(fault, "KEEP_OUT"),
        "keep_in_faults": pc.equal(fault, "KEEP_IN"),
        "faults": pc.not_equal(fault, ""),
        "onboard_localizations_applied": pc.fill_null(applied, False),
        "onboard_localizations_rejected": pc.fill_null(pc.invert(applied), False),
        "ground_localizations": sols.column("ground_localized"),
        "truth_outside_disc_sols": pc.fill_null(pc.invert(sols.column("truth_inside_disc")), False),
        "max_truth_error_m": sols.column("truth_error_m"),
        "goal_reached": sols.column("reached_goal"),
        "max_end_uncertainty_m": sols.column("end_uncertainty_m"),
    })
    how = {name: "sum" for name in per_sol.column_names[2:]}
    how.update(max_truth_error_m="max", goal_reached="any", max_end_uncertainty_m="max")
    agg = per_sol.group_by(["run_index", "strategy"]).aggregate(
        [(name, f) for name, f in how.items()])
    derived = {(r["run_index"], r["strategy"]): r for r in agg.to_pylist()}
    uplinks = sols.filter(sols.column("drove")).group_by(["run_index", "strategy"]).aggregate(
        [("plan_uplink_sol", "count_distinct")])
    plan_uplinks = {(r["run_index"], r["strategy"]): r["plan_uplink_sol_count_distinct"]
                    for r in uplinks.to_pylist()}
    for row in runs.to_pylist():
        k = (row["run_index"], row["strategy"])
        if k not in derived:
            continue
        where = f"runs.parquet (run {k[0]}, {k[1]})"
        for name, f in how.items():
            if name == "max_end_uncertainty_m":
                continue
            got, want = row[name], derived[k][f"{name}_{f}"]
            if isinstance(got, float):
                problems.close(where, f"{name} against sols.parquet", got, want, 1.0)
            else:
                problems.equal(where, f"{name} against sols.parquet", got, want)
        problems.equal(where, "drive_plan_uplinks against sols.parquet (distinct "
                              "plan_uplink_sol of the sols that drove)",
                       row["drive_plan_uplinks"], plan_uplinks.get(k, 0))
        max_end_r = derived[k]["max_end_uncertainty_m_max"]
        if row["max_uncertainty_m"] < max_end_r:
            problems.add(where, f"max_uncertainty_m {row['max_uncertainty_m']} below the "
                                f"largest end_uncertainty_m of its sols ({max_end_r})")


def check_nulls(problems, runs, sols, manifest):
    """Each nullable column is null exactly when docs/sweep-schema.md says."""
    import pyarrow.compute as pc

    def null(t, name):
        return pc.is_null(t.column(name))

    def given(t, name):
        return pc.is_valid(t.column(name))

    def is_(t, name, value):
        return pc.fill_null(pc.equal(t.column(name), value), False)

    drove = sols.column("drove")
    has_segment = manifest.get("segment") is not None
    rules = [
        ("runs.parquet", "sols_to_goal", "null exactly when goal_reached is false",
         pc.equal(null(runs, "sols_to_goal"), pc.invert(runs.column("goal_reached")))),
        ("runs.parquet", "segment_distance_m",
         f"{'set' if has_segment else 'null'} (manifest.json segment: "
         f"{'set' if has_segment else 'null'})",
         pc.equal(given(runs, "segment_distance_m"), has_segment)),
        ("runs.parquet", "segment_sols", "null when the manifest has no segment",
         pc.or_(has_segment, null(runs, "segment_sols"))),
        ("sols.parquet", "skip_reason", "null exactly when drove",
         pc.equal(null(sols, "skip_reason"), drove)),
        ("sols.parquet", "fault_after_m", "null exactly when fault is",
         pc.equal(null(sols, "fault_after_m"), null(sols, "fault"))),
        ("sols.parquet", "fault_uncertainty_m", "null exactly when fault is",
         pc.equal(null(sols, "fault_uncertainty_m"), null(sols, "fault"))),
        ("sols.parquet", "fault", "null when the rover did not drive",
         pc.or_(drove, null(sols, "fault"))),
        ("sols.parquet", "passage_clearance_m", "null when the rover did not drive",
         pc.or_(drove, null(sols, "passage_clearance_m"))),
        ("sols.parquet", "onboard_applied", "null exactly when onboard_localization is false",
         pc.equal(null(sols, "onboard_applied"), pc.invert(sols.column("onboard_localization")))),
        ("sols.parquet", "onboard_rejection", "set exactly when onboard_applied is false",
         pc.equal(given(sols, "onboard_rejection"), is_(sols, "onboard_applied", False))),
        ("sols.parquet", "onboard_error_m", "set exactly when onboard_applied is true",
         pc.equal(given(sols, "onboard_error_m"), is_(sols, "onboard_applied", True))),
    ]
    for table, column, rule, holds in rules:
        broken = len(holds) - pc.sum(holds.cast("int64")).as_py() if len(holds) else 0
        if broken:
            problems.add(table, f"column {column!r} breaks the documented rule ({rule}) in "
                                f"{broken} rows")


def check_summary(problems, summary, runs, manifest):
    import numpy as np

    where = "summary.json"
    for key in ("format", "scenario", "seed", "runs", "shard", "segment"):
        problems.equal(where, f"{key} (as in manifest.json)", summary.get(key),
                       manifest.get(key))
    st = summary.get("statistics", {})
    problems.equal(where, "statistics.baseline (as in manifest.json)", st.get("baseline"),
                   manifest.get("baseline"))
    names = [s["strategy"] for s in st.get("strategies", [])]
    problems.equal(where, "statistics.strategies (as in manifest.json)", names,
                   manifest["strategies"])
    strategy = np.array(runs.column("strategy").to_pylist(), dtype=object)
    run_index = np.array(runs.column("run_index").to_pylist())

    def column(name, s):
        """The non-null values of a runs.parquet column for strategy `s`, as float64 (bool
        columns as numpy bools), with their run indices."""
        c = runs.column(name).to_pylist()
        keep = [k for k in range(len(c)) if strategy[k] == s and c[k] is not None]
        values = [c[k] for k in keep]
        as_bool = runs.schema.field(name).type == "bool"
        return (np.array(values, dtype=bool if as_bool else np.float64),
                {int(run_index[k]): values[i] for i, k in enumerate(keep)})

    for ss in st.get("strategies", []):
        s = ss["strategy"]
        w = f"{where} (strategy {s})"
        n = int(np.sum(strategy == s))
        problems.equal(w, "runs", ss["runs"], n)
        problems.equal(w, "rates", sorted(r["name"] for r in ss["rates"]),
                       sorted(RATES) if n else [])
        for rate in ss["rates"]:
            if rate["name"] not in RATES:
                problems.add(w, f"rate {rate['name']!r}: unknown to this check (add it to RATES)")
                continue
            col, counts = RATES[rate["name"]]
            values, _ = column(col, s)
            count = int(np.sum(counts(values)))
            problems.equal(w, f"{rate['name']}.count ({col})", rate["count"], count)
            problems.equal(w, f"{rate['name']}.runs", rate["runs"], n)
            problems.close(w, f"{rate['name']}.rate", rate["rate"], count / n if n else None, 0)
            lo, hi = rate["interval"]["lo"], rate["interval"]["hi"]
            if not 0.0 <= lo <= rate["rate"] <= hi <= 1.0:
                problems.add(w, f"{rate['name']}.interval [{lo}, {hi}] does not hold the rate "
                                f"{rate['rate']} within [0, 1]")
        drive_sols, _ = column("drive_sols", s)
        outside, _ = column("truth_outside_disc_sols", s)
        sols = int(np.sum(drive_sols))
        cov = ss.get("disc_coverage")
        if sols == 0:
            problems.equal(w, "disc_coverage (no drive sol)", cov, None)
        elif cov is None:
            problems.add(w, "disc_coverage missing")
        else:
            inside = sols - int(np.sum(outside))
            problems.equal(w, "disc_coverage.count (drive sols inside the disc)", cov["count"],
                           inside)
            problems.equal(w, "disc_coverage.runs (drive sols)", cov["runs"], sols)
            problems.close(w, "disc_coverage.rate", cov["rate"], inside / sols, 0)
        for fig in ss["figures"]:
            if fig["name"] not in runs.column_names:
                problems.add(w, f"figure {fig['name']!r}: not a runs.parquet column")
                continue
            values, _ = column(fig["name"], s)
            spread = fig["spread"]
            if len(values) == 0:
                problems.equal(w, f"figure {fig['name']}", spread, None)
                continue
            if spread is None:
                problems.add(w, f"figure {fig['name']}: expected a spread of {len(values)} "
                                f"values, got null")
                continue
            scale = float(np.max(np.abs(values)))
            problems.equal(w, f"{fig['name']}.n", spread["n"], len(values))
            problems.close(w, f"{fig['name']}.mean", spread["mean"], float(np.mean(values)),
                           scale)
            problems.close(w, f"{fig['name']}.median", spread["median"],
                           float(np.median(values)), scale)
            for key, q in (("p5", 0.05), ("p95", 0.95)):
                problems.close(w, f"{fig['name']}.{key}", spread[key],
                               float(np.quantile(values, q)), scale)

    baseline = manifest.get("baseline")
    for p in st.get("paired", []):
        w = f"{where} (paired {p['strategy']} − {baseline}, {p['figure']})"
        if baseline is None:
            problems.add(w, "a paired difference without a baseline")
            continue
        _, mine = column(p["figure"], p["strategy"])
        _, base = column(p["figure"], baseline)
        diffs = np.array([mine[i] - base[i] for i in sorted(mine) if i in base],
                         dtype=np.float64)
        d = p["difference"]
        if len(diffs) == 0:
            problems.equal(w, "difference", d, None)
            continue
        if d is None:
            problems.add(w, f"expected a difference over {len(diffs)} pairs, got null")
            continue
        scale = max(float(np.max(np.abs(list(mine.values())))),
                    float(np.max(np.abs(list(base.values())))))
        problems.equal(w, "n", d["n"], len(diffs))
        problems.close(w, "mean", d["mean"], float(np.mean(diffs)), scale)
        if not d["interval"]["lo"] <= d["interval"]["hi"]:
            problems.add(w, f"interval [{d['interval']['lo']}, {d['interval']['hi']}] reversed")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("sweep_dir", type=Path, help="a complete `solsim sweep` output directory")
    ap.add_argument("--schema", type=Path, default=PEERS.parent / "tests" / "sweep_schema.json",
                    help="the documented schema (default: tests/sweep_schema.json)")
    args = ap.parse_args()
    ensure_venv("pyarrow, numpy")
    try:
        import pyarrow.parquet as pq
    except ImportError as e:
        fail_usage(f"{e}: install peers/requirements.txt into {sys.prefix} "
                   f"({sys.prefix}/bin/pip install -r {PEERS / 'requirements.txt'})")

    schema_doc = load_json(args.schema)
    for key in ("format", *TABLES):
        if key not in schema_doc:
            fail_usage(f"{args.schema}: no {key!r} entry")
    d = args.sweep_dir
    for name in (*TABLES, "manifest.json", "summary.json"):
        if not (d / name).is_file():
            fail_usage(f"{d / name}: no such file (not a complete sweep directory)")
    manifest = load_json(d / "manifest.json")
    summary = load_json(d / "summary.json")

    problems = Problems()
    check_manifest(problems, d, manifest, schema_doc)
    tables = {}
    columns_ok = True
    for name in TABLES:
        try:
            pf = pq.ParquetFile(d / name)
            tables[name] = pf.read()
        except Exception as e:  # noqa: BLE001 - any decoder error is a finding, on one line
            fail_usage(f"{d / name}: pyarrow cannot read it: {e}")
        columns_ok &= check_columns(problems, name, tables[name].schema, schema_doc[name])
        check_metadata(problems, name, pf.metadata.metadata, manifest)
    if columns_ok:
        # Row checks index columns by their documented names and types.
        check_rows(problems, tables["runs.parquet"], tables["sols.parquet"], manifest)
        check_nulls(problems, tables["runs.parquet"], tables["sols.parquet"], manifest)
        check_summary(problems, summary, tables["runs.parquet"], manifest)

    if problems.lines:
        for line in problems.lines:
            print(f"sweep_schema_check: {d}/{line}", file=sys.stderr)
        print(f"sweep_schema_check: {len(problems.lines)} difference(s) from the documented "
              f"schema, manifest.json or summary.json", file=sys.stderr)
        sys.exit(1)
    runs, sols = tables["runs.parquet"], tables["sols.parquet"]
    print(f"ok: {d}: runs.parquet {runs.num_rows} rows × {runs.num_columns} columns, "
          f"sols.parquet {sols.num_rows} rows × {sols.num_columns} columns, "
          f"{len(manifest['strategies'])} strategies; schema, metadata, row counts and "
          f"summary.json agree")


if __name__ == "__main__":
    main()
