#!/usr/bin/env python3
"""Peer timings for the grid benchmarks B3 (keep-out growth) and B4 (A*), and the ratio table.

Usage:
    peers/bench_grid.py peers  [--grids DIR] [--runs N] [--out FILE]
    peers/bench_grid.py report [--grids DIR] [--criterion DIR] [--out FILE]

`peers` times the peers on the exact problem instances that `cargo bench --bench grid` dumps
when run with SOLSIM_GRID_DUMP=DIR (default target/bench-grids; see benches/grid.rs):

* B3: ``cv2.distanceTransform(free, DIST_L2, DIST_MASK_PRECISE) <= r`` with cv2.setNumThreads(1)
  and (2); ``scipy.ndimage.distance_transform_edt(free) <= r`` as context. Both grown sets are
  compared cell by cell with ours (grown_<n>_r10.npy).
* B4: ``pyastar2d.astar_path(weights, start, goal, allow_diagonal=True)``. pyastar2d's move
  model differs from ours: every move, diagonal or not, costs ``weights[next]`` and diagonal
  moves may cut corners; its heuristic is the Chebyshev distance. So its path cost is reported
  in its own model and, for comparison, re-costed in ours (step length x weight), with the
  number of corner cuts.

Each figure is the median, min and max of N runs (default 5) after one warm-up run.
`peers` re-runs itself inside peers/.venv, creating it from peers/requirements.txt if needed.

`report` needs only the standard library: it reads the criterion results of the same job
(<criterion>/B3_keepout/... and B4_astar/..., per-iteration times from sample.json) and the
peers' JSON, and prints the ratio table (ours / peer; < 1 means we are faster).
"""

import argparse
import json
import os
import statistics
import sys
from pathlib import Path

from peer_common import cpu_model, ensure_venv, timed

PEERS = Path(__file__).resolve().parent
ROOT = PEERS.parent
RADIUS_CELLS = 10.0


def sizes_in(grids):
    return sorted(int(p.stem.split("_")[1]) for p in grids.glob("mask_*.npy"))


def run_peers(args):
    ensure_venv("cv2, numpy, scipy, pyastar2d")
    import cv2
    import numpy as np
    import pyastar2d
    import scipy
    from scipy import ndimage

    grids = Path(args.grids)
    sizes = sizes_in(grids)
    if not sizes:
        sys.exit(f"no mask_<n>.npy in {grids}: run the bench with SOLSIM_GRID_DUMP={grids}")
    out = {
        "cpu": cpu_model(), "cores": os.cpu_count(),
        "versions": {"numpy": np.__version__, "scipy": scipy.__version__,
                     "opencv": cv2.__version__, "pyastar2d": "1.1.4 (requirements.txt)"},
        "b3": {}, "b4": {},
    }
    for n in sizes:
        mask = np.load(grids / f"mask_{n}.npy")
        ours = np.load(grids / f"grown_{n}_r10.npy")
        free = np.where(mask, 0, 255).astype(np.uint8)  # distances are to the zero cells
        b3 = {}
        for threads in (1, 2):
            cv2.setNumThreads(threads)
            dist, st = timed(lambda: cv2.distanceTransform(free, cv2.DIST_L2,
                                                           cv2.DIST_MASK_PRECISE), args.runs)
            grown, st_g = timed(lambda: cv2.distanceTransform(
                free, cv2.DIST_L2, cv2.DIST_MASK_PRECISE) <= RADIUS_CELLS, args.runs)
            b3[f"cv2_precise_{threads}thr"] = {**st_g, "edt_only": st,
                                               "same_as_ours": bool(np.array_equal(grown, ours))}
        cv2.setNumThreads(1)
        free_b = ~mask
        grown, st = timed(lambda: ndimage.distance_transform_edt(free_b) <= RADIUS_CELLS,
                          args.runs)
        b3["scipy_edt_1thr"] = {**st, "same_as_ours": bool(np.array_equal(grown, ours))}
        b3["grown_cells"] = int(ours.sum())
        out["b3"][str(n)] = b3
        print(f"B3 {n}²: " + ", ".join(
            f"{k} {v['median_ms']:.1f} ms (same: {v['same_as_ours']})"
            for k, v in b3.items() if isinstance(v, dict)), flush=True)

        weights = np.load(grids / f"weights_{n}.npy")
        meta = json.loads((grids / f"astar_{n}.json").read_text())
        start, goal = tuple(meta["start"]), tuple(meta["goal"])
        path, st = timed(lambda: pyastar2d.astar_path(weights, start, goal,
                                                      allow_diagonal=True), args.runs)
        b4 = {"pyastar2d": st, "ours": meta}
        if path is not None:
            rows, cols = path[:, 0], path[:, 1]
            w_next = weights[rows[1:], cols[1:]].astype(np.float64)
            diag = (rows[1:] != rows[:-1]) & (cols[1:] != cols[:-1])
            cuts = diag & ((weights[rows[:-1], cols[1:]] == np.inf)
                           | (weights[rows[1:], cols[:-1]] == np.inf))
            st["path_cells"] = int(len(path))
            st["cost_own_model"] = float(w_next.sum())
            st["cost_in_our_model"] = float((w_next * np.where(diag, np.sqrt(2.0), 1.0)).sum())
            st["corner_cuts"] = int(cuts.sum())
        out["b4"][str(n)] = b4
        print(f"B4 {n}²: pyastar2d {st['median_ms']:.1f} ms, cost (own model) "
              f"{st.get('cost_own_model')}, in our model {st.get('cost_in_our_model')} "
              f"({st.get('corner_cuts')} corner cuts); ours {meta['cost']}", flush=True)
    text = json.dumps(out, indent=1)
    if args.out:
        Path(args.out).write_text(text + "\n")
    else:
        print(text)


def criterion_stats(criterion, bench):
    """Median/min/max per-iteration time (ms) of one criterion benchmark, or None."""
    sample = Path(criterion) / bench / "new" / "sample.json"
    if not sample.exists():
        return None
    data = json.loads(sample.read_text())
    per_iter = [t / i / 1e6 for t, i in zip(data["times"], data["iters"])]
    return {"median_ms": statistics.median(per_iter), "min_ms": min(per_iter),
            "max_ms": max(per_iter), "runs": len(per_iter)}


def report(args):
    peers = json.loads(Path(args.peers).read_text())
    rows = []

    def row(what, n, ours, peer_name, peer):
        if ours is None or peer is None:
            return
        rows.append((what, n, ours, peer_name, peer, ours["median_ms"] / peer["median_ms"]))

    for n, b3 in peers["b3"].items():
        for threads in (1, 2):
            ours = criterion_stats(args.criterion, f"B3_keepout/grow_r10_{threads}thr/{n}")
            two = criterion_stats(args.criterion,
                                  f"B3_keepout/edt_then_threshold_{threads}thr/{n}")
            cv = b3.get(f"cv2_precise_{threads}thr")
            row(f"B3 grow r=10, {threads} thr", n, ours, f"cv2 PRECISE + threshold, {threads} thr", cv)
            row(f"B3 squared_edt + threshold, {threads} thr", n, two,
                f"cv2 PRECISE + threshold, {threads} thr", cv)
            row(f"B3 grow r=10, {threads} thr", n, ours, "scipy EDT + threshold, 1 thr",
                b3.get("scipy_edt_1thr"))
    for n, b4 in peers["b4"].items():
        ours = criterion_stats(args.criterion, f"B4_astar/corner_to_corner/{n}")
        row("B4 A* corner to corner", n, ours, "pyastar2d (8-conn)", b4.get("pyastar2d"))

    print(f"CPU: {peers['cpu']} ({peers['cores']} cores)")
    print(f"{'benchmark':42} {'n':>5} {'ours median [min-max] ms':>28}  "
          f"{'peer':38} {'peer median [min-max] ms':>28} {'ratio':>6}")
    for what, n, o, pname, p, ratio in rows:
        fmt = lambda s: f"{s['median_ms']:.1f} [{s['min_ms']:.1f}-{s['max_ms']:.1f}]"
        print(f"{what:42} {n:>5} {fmt(o):>28}  {pname:38} {fmt(p):>28} {ratio:6.2f}")
    for n, b3 in peers["b3"].items():
        same = {k: v["same_as_ours"] for k, v in b3.items() if isinstance(v, dict)}
        print(f"B3 {n}²: grown set identical to ours: {same}")
    for n, b4 in peers["b4"].items():
        ours, py = b4["ours"], b4["pyastar2d"]
        ours_t = criterion_stats(args.criterion, f"B4_astar/corner_to_corner/{n}")
        rate = (f", {ours['expansions'] / (ours_t['median_ms'] / 1e3) / 1e6:.2f} M expansions/s"
                if ours_t else "")
        print(f"B4 {n}²: ours cost {ours['cost']:.3f} ({ours['expansions']} expansions{rate}); "
              f"pyastar2d cost {py.get('cost_own_model')} in its model, "
              f"{py.get('cost_in_our_model')} in ours ({py.get('corner_cuts')} corner cuts)")
    if args.out:
        Path(args.out).write_text(json.dumps(
            [dict(zip(("benchmark", "n", "ours", "peer_name", "peer", "ratio"), r))
             for r in rows], indent=1) + "\n")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    sub = ap.add_subparsers(dest="cmd", required=True)
    p = sub.add_parser("peers", help="time the Python peers")
    p.add_argument("--grids", default=str(ROOT / "target" / "bench-grids"))
    p.add_argument("--runs", type=int, default=5)
    p.add_argument("--out")
    r = sub.add_parser("report", help="print the ratio table")
    r.add_argument("--peers", default=str(ROOT / "target" / "bench-grids" / "peers.json"))
    r.add_argument("--criterion", default=str(ROOT / "target" / "criterion"))
    r.add_argument("--out")
    args = ap.parse_args()
    run_peers(args) if args.cmd == "peers" else report(args)


if __name__ == "__main__":
    main()
