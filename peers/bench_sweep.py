#!/usr/bin/env python3
"""Peers for the sweep's two non-simulation hot paths (BENCHMARKS.md, "Monte Carlo sweeps").

Loads what `cargo bench --bench sweep` dumps with SOLSIM_SWEEP_DUMP=<dir>:
`sols.parquet` (the benchmark's sols table, written by solsim) and `diffs.txt` (the 1000 paired
differences the bootstrap benchmark resamples), and times what a user would otherwise run:

- `pyarrow_write_table`: `pq.write_table(table, path, compression="snappy",
  row_group_size=65536)` of the same table (read once with pyarrow, then written);
- `scipy_bootstrap`: `scipy.stats.bootstrap((d,), np.mean, n_resamples=10000,
  confidence_level=0.95, method="percentile", rng=np.random.default_rng(7))` (vectorised).

Each is timed after one warm-up, >= 5 runs; median, min and max in ms.

Usage:
  peers/bench_sweep.py peers  --dump DIR [--runs N] [--out peers.json]
  peers/bench_sweep.py report --peers peers.json --criterion target/bench-native/criterion

`peers` re-runs itself inside peers/.venv, creating it from peers/requirements.txt if needed.
"""
import argparse
import json
import sys
import tempfile
from pathlib import Path

from peer_common import cpu_model, ensure_venv, timed


def cmd_peers(args):
    ensure_venv("numpy, scipy, pyarrow")
    import numpy as np
    import pyarrow.parquet as pq
    import scipy
    import scipy.stats as st

    dump = Path(args.dump)
    table = pq.read_table(dump / "sols.parquet")
    diffs = np.array([float(x) for x in (dump / "diffs.txt").read_text().split()])
    results = {}
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / "sols.parquet"
        _, results["pyarrow_write_table"] = timed(
            lambda: pq.write_table(table, out, compression="snappy", row_group_size=65536),
            args.runs)
        results["pyarrow_write_table"]["rows"] = table.num_rows
        results["pyarrow_write_table"]["bytes"] = out.stat().st_size
    ci, results["scipy_bootstrap"] = timed(
        lambda: st.bootstrap((diffs,), np.mean, n_resamples=10_000, confidence_level=0.95,
                             method="percentile", rng=np.random.default_rng(7)).confidence_interval,
        args.runs)
    results["scipy_bootstrap"]["interval"] = [float(ci.low), float(ci.high)]
    import pyarrow
    doc = {"cpu": cpu_model(), "versions": {"numpy": np.__version__, "scipy": scipy.__version__,
                                            "pyarrow": pyarrow.__version__},
           "results": results}
    text = json.dumps(doc, indent=2)
    if args.out:
        Path(args.out).write_text(text + "\n")
    print(text)


def criterion_ms(root, group, bench):
    p = Path(root) / group / bench / "new" / "estimates.json"
    return json.loads(p.read_text())["median"]["point_estimate"] / 1e6


def cmd_report(args):
    peers = json.loads(Path(args.peers).read_text())
    res = peers["results"]
    print(f"CPU: {peers['cpu']}; {peers['versions']}")
    print(f"{'benchmark':34s} {'ours ms':>9s} {'peer':>22s} {'peer ms':>9s} {'ours/peer':>9s}")
    for ours, peer in (("parquet_sols_table", "pyarrow_write_table"),
                       ("paired_bootstrap_1000_x_10000", "scipy_bootstrap")):
        o = criterion_ms(args.criterion, "sweep", ours)
        p = res[peer]["median_ms"]
        print(f"{ours:34s} {o:9.2f} {peer:>22s} {p:9.2f} {o / p:9.3f}")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    sub = ap.add_subparsers(dest="cmd", required=True)
    p = sub.add_parser("peers")
    p.add_argument("--dump", required=True)
    p.add_argument("--runs", type=int, default=7)
    p.add_argument("--out")
    r = sub.add_parser("report")
    r.add_argument("--peers", required=True)
    r.add_argument("--criterion", required=True)
    args = ap.parse_args()
    {"peers": cmd_peers, "report": cmd_report}[args.cmd](args)


if __name__ == "__main__":
    sys.exit(main())
