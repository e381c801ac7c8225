#!/usr/bin/env python3
"""Peers for the filter benchmarks (benches/filters.rs): one EKF step and the particle filter's
resampling and reweighting, on the instances `cargo bench --bench filters` dumps with
SOLSIM_FILTERS_DUMP=<dir>.

- `filterpy_ekf`: filterpy 2.0.0's ExtendedKalmanFilter with the model of peers/ekf_filterpy.py
  (imported from it: its RK4 `predict_x` and the transition matrix I + FΔt + (FΔt)²/2 + (FΔt)³/6
  set by `set_step`), so `predict()` does P = F P F' + Q; then `update(z, HJacobian, Hx, R)`
  with the range model (Jacobian and h written as in ekf_filterpy.py). One step = set_step +
  predict + update, over the 860 consecutive seconds with a range of `ekf_window.json`, from our
  state one second before; per step = run time / 860. The peer must end at our state and
  covariance (|Δx_i| <= 1e-6 max(|x_i|, σ_i), |ΔP_ij| <= 1e-6 sqrt(P_ii P_jj), as
  tests/ekf_filterpy.rs checks), or the script exits non-zero.
  `filterpy_ekf_predict`: set_step + predict only.
- `numpy_ekf`: the same arithmetic written directly in numpy (no filterpy bookkeeping: no copies
  of x_prior/x_post, no deepcopy(z), no linalg.inv of the 1x1 S), to show how much of the
  filterpy time is filterpy and how much is Python + numpy on 8x8 matrices. Also checked
  against our end state.
- `filterpy_systematic`: filterpy.monte_carlo.systematic_resample(weights) on our weights
  (a Python while loop over the particles); `numpy_systematic`: the vectorised
  np.searchsorted(np.cumsum(w), (u0 + arange(N)) / N, side='right') a user would write. Both
  must give our indices for our u0 (filterpy's offset is patched to u0 for that check only; the
  timed calls use its own numpy `random()`).
- `numpy_reweight`: the particle weight update without the score surface, vectorised:
  likelihood exp(-(s - s_min)/T) from our per-particle scores (NaN = 0), multiply, normalise,
  effective sample size, and when it falls below N/2 systematic resampling (searchsorted) plus
  N(0, roughening²) jitter, against `ParticleFilter::update_with_scores`. Its effective sample
  size must equal ours to 1e-9 (relative).

Each peer: one warm-up + N runs (default 7), each run a batch of calls sized to take
>= 50 ms; median (min-max) per call.

Usage:
  peers/bench_filters.py peers  --dump DIR [--runs N] [--out peers.json]
  peers/bench_filters.py report --peers peers.json --criterion target/bench-native/criterion

`peers` re-runs itself inside peers/.venv, creating it from peers/requirements.txt if needed.
"""
import argparse
import json
import math
import sys
import time
from pathlib import Path

from peer_common import cpu_model, ensure_venv, timed

COUNTS = (1000, 5000)


def batch_size(fn, target_s=0.05):
    """Calls per timed run so that a run takes about `target_s` (at least 1), from the mean of
    three calls after a first (cold) one."""
    fn()
    t0 = time.perf_counter()
    for _ in range(3):
        fn()
    dt = (time.perf_counter() - t0) / 3
    return max(1, math.ceil(target_s / max(dt, 1e-9)))


def per_call(fn, runs):
    """(result, stats in µs per call): `timed` over runs of `reps` calls each."""
    reps = batch_size(fn)

    def run():
        for _ in range(reps):
            out = fn()
        return out

    result, stats = timed(run, runs)
    return result, {"median_us": stats["median_ms"] * 1e3 / reps,
                    "min_us": stats["min_ms"] * 1e3 / reps,
                    "max_us": stats["max_ms"] * 1e3 / reps,
                    "calls_per_run": reps, "runs": runs}


# --- EKF ---------------------------------------------------------------------------------------

def ekf_close(x, P, x_ref, P_ref, np):
    """tests/ekf_filterpy.rs's tolerance: (ok, worst relative state and covariance error)."""
    x, P = np.asarray(x).ravel(), np.asarray(P)
    sig = np.sqrt(np.diag(P_ref))
    dx = np.abs(x - x_ref) / np.maximum(np.abs(x_ref), sig)
    dP = np.abs(P - P_ref) / np.sqrt(np.outer(np.diag(P_ref), np.diag(P_ref)))
    return bool(dx.max() <= 1e-6 and dP.max() <= 1e-6), float(dx.max()), float(dP.max())


def ekf_peers(d, runs, results):
    import numpy as np
    from ekf_filterpy import EAST, NORTH, Frame, RoverEKF, derivative, jacobian
    inst = json.loads((d / "ekf_window.json").read_text())
    frame = Frame(inst["frame"])
    x0 = np.asarray(inst["x0"], float).reshape(8, 1)
    P0 = np.asarray(inst["P0"], float)
    Q = np.asarray(inst["Q"], float)
    r_range = np.array([[inst["range_variance_m2"]]])
    x_end, P_end = np.asarray(inst["x_end"], float), np.asarray(inst["P_end"], float)
    # Inputs prepared once, as the Rust side holds them in memory.
    steps = [(s["u0"], s["u1"], float(s["u1"]["t_s"] - s["u0"]["t_s"]), float(s["t_s"]),
              np.array([[s["range_m"]]]), np.asarray(s["orbiter_mci_m"], float))
             for s in inst["steps"]]
    k = len(steps)

    # The range model as peers/ekf_filterpy.py writes it (there a closure inside main()).
    def range_h(x, t, r_o):
        return np.array([[np.linalg.norm(frame.rover_mci(t, x[EAST, 0], x[NORTH, 0]) - r_o)]])

    def range_jac(x, t, r_o):
        dd = frame.rover_mci(t, x[EAST, 0], x[NORTH, 0]) - r_o
        u = dd / np.linalg.norm(dd)
        rot = frame.rot(t)
        h = np.zeros((1, 8))
        h[0, EAST], h[0, NORTH] = u @ (rot @ frame.east), u @ (rot @ frame.north)
        return h

    ekf = RoverEKF(dim_x=8, dim_z=1)
    ekf.Q = Q

    def filterpy_window(update=True):
        ekf.x, ekf.P = x0.copy(), P0.copy()
        for u0, u1, dt, t, z, r_o in steps:
            ekf.set_step(u0, u1, dt)
            ekf.predict()
            if update:
                ekf.update(z, range_jac, range_h, R=r_range, args=(t, r_o), hx_args=(t, r_o))
        return ekf.x.copy(), ekf.P.copy()

    # The same arithmetic without filterpy: RK4 (ekf_filterpy's derivative), Φ from its
    # jacobian, P = Φ P Φ' + Q, the range update in Joseph form.
    eye = np.eye(8)

    def numpy_window():
        x, P = x0.copy(), P0.copy()
        for u0, u1, dt, t, z, r_o in steps:
            a0, a1 = np.asarray(u0["accel"][:2]), np.asarray(u1["accel"][:2])
            w0, w1 = u0["yaw_rate"], u1["yaw_rate"]
            am, wm = 0.5 * (a0 + a1), 0.5 * (w0 + w1)
            fdt = jacobian(x, am) * dt
            f2 = fdt @ fdt
            phi = eye + fdt + f2 / 2.0 + f2 @ fdt / 6.0
            k1 = derivative(x, a0, w0)
            k2 = derivative(x + 0.5 * dt * k1, am, wm)
            k3 = derivative(x + 0.5 * dt * k2, am, wm)
            k4 = derivative(x + dt * k3, a1, w1)
            x = x + dt / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4)
            P = phi @ P @ phi.T + Q
            h = range_jac(x, t, r_o)
            pht = P @ h.T
            s = (h @ pht)[0, 0] + r_range[0, 0]
            gain = pht / s
            x = x + gain * (z[0, 0] - range_h(x, t, r_o)[0, 0])
            i_kh = eye - gain @ h
            P = i_kh @ P @ i_kh.T + (gain * r_range[0, 0]) @ gain.T
        return x, P

    ok = True
    for name, fn, check in (("filterpy_ekf", filterpy_window, True),
                            ("filterpy_ekf_predict", lambda: filterpy_window(False), False),
                            ("numpy_ekf", numpy_window, True)):
        (x, P), stats = timed(fn, runs)
        st = {"median_us": stats["median_ms"] * 1e3 / k, "min_us": stats["min_ms"] * 1e3 / k,
              "max_us": stats["max_ms"] * 1e3 / k, "steps_per_run": k, "runs": runs}
        line = ""
        if check:
            close, ex, ep = ekf_close(x, P, x_end, P_end, np)
            st.update(matches_ours=close, max_rel_dx=ex, max_rel_dP=ep)
            ok &= close
            line = (f"  end state vs ours: max rel dx {ex:.1e}, dP {ep:.1e} "
                    f"{'(ok)' if close else '(MISMATCH)'}")
        results[name] = st
        print(f"{name:22s} {st['median_us']:9.2f} µs/step (min {st['min_us']:.2f}, max "
              f"{st['max_us']:.2f}; {runs} runs of {k} steps){line}")
    return ok


# --- particle filter ---------------------------------------------------------------------------

def numpy_systematic(w, u0, np):
    n = len(w)
    idx = np.searchsorted(np.cumsum(w), (u0 + np.arange(n)) / n, side="right")
    # As solsim: a pointer past the rounded total goes to the last particle with weight.
    return np.minimum(idx, np.flatnonzero(w > 0)[-1])


def resample_peers(d, runs, results):
    import numpy as np
    import filterpy.monte_carlo as mc
    import filterpy.monte_carlo.resampling as mc_resampling
    ok = True
    for n in COUNTS:
        w = np.load(d / f"pf_weights_{n}.npy").ravel()
        ours = np.load(d / f"pf_indices_{n}.npy").ravel()
        u0 = json.loads((d / f"pf_resample_{n}.json").read_text())["u0"]
        # Same indices for the same offset.
        real_random = mc_resampling.random
        mc_resampling.random = lambda: u0
        try:
            same_fp = bool(np.array_equal(mc.systematic_resample(w), ours))
        finally:
            mc_resampling.random = real_random
        same_np = bool(np.array_equal(numpy_systematic(w, u0, np), ours))
        ok &= same_fp and same_np
        for name, fn, same in ((f"filterpy_systematic/{n}", lambda: mc.systematic_resample(w),
                                same_fp),
                               (f"numpy_systematic/{n}", lambda: numpy_systematic(w, u0, np),
                                same_np)):
            _, st = per_call(fn, runs)
            st["indices_match_ours"] = same
            results[name] = st
            print(f"{name:22s} {st['median_us']:9.2f} µs (min {st['min_us']:.2f}, max "
                  f"{st['max_us']:.2f}; {runs} runs of {st['calls_per_run']} calls)  indices "
                  f"{'== ours' if same else '!= ours'}")
    return ok


def reweight_peers(d, runs, results):
    import numpy as np
    ok = True
    rng = np.random.default_rng(2026)
    for n in COUNTS:
        pos = np.load(d / f"pf_particles_{n}.npy")
        scores = np.load(d / f"pf_scores_{n}.npy").ravel()
        ours = json.loads((d / f"pf_reweight_{n}.json").read_text())
        t, thr, rough = ours["temperature"], ours["resample_threshold"], ours["roughening_m"]
        w0 = np.full(n, 1.0 / n)

        def reweight():
            usable = np.isfinite(scores) & (w0 > 0)
            best = scores[usable].min()
            lik = np.where(usable, np.exp(-(np.where(usable, scores, best) - best) / t), 0.0)
            w = w0 * lik
            w = w / w.sum()
            ess = 1.0 / np.dot(w, w)
            if ess < thr * n:
                idx = numpy_systematic(w, rng.random(), np)
                p = pos[idx] + rough * rng.standard_normal((n, 2))
                return p, np.full(n, 1.0 / n), ess, True
            return pos, w, ess, False

        (_, _, ess, resampled), st = per_call(reweight, runs)
        same = (abs(ess - ours["effective_sample_size"]) <= 1e-9 * ours["effective_sample_size"]
                and resampled == ours["resampled"])
        ok &= same
        st.update(effective_sample_size=float(ess), resampled=bool(resampled),
                  matches_ours=bool(same))
        results[f"numpy_reweight/{n}"] = st
        print(f"{'numpy_reweight/' + str(n):22s} {st['median_us']:9.2f} µs (min "
              f"{st['min_us']:.2f}, max {st['max_us']:.2f}; {runs} runs of "
              f"{st['calls_per_run']} calls)  ESS {ess:.4f} (ours "
              f"{ours['effective_sample_size']:.4f}), resampled {resampled}")
    return ok


def cmd_peers(args):
    ensure_venv("filterpy, numpy")
    import filterpy
    import numpy as np
    d = Path(args.dump)
    results = {}
    ok = ekf_peers(d, args.runs, results)
    ok &= resample_peers(d, args.runs, results)
    ok &= reweight_peers(d, args.runs, results)
    out = {"cpu": cpu_model(), "numpy": np.__version__, "filterpy": filterpy.__version__,
           "python": sys.version.split()[0], "results": results}
    if args.out:
        Path(args.out).write_text(json.dumps(out, indent=1))
    if not ok:
        sys.exit("filter peers: a peer did not reproduce our result")


def criterion_us(root, *path):
    p = Path(root).joinpath(*path, "new", "estimates.json")
    est = json.loads(p.read_text())
    return est["median"]["point_estimate"] / 1e3


def fmt_us(v):
    return f"{v / 1e3:.2f} ms" if v >= 1000 else f"{v:.2f} µs" if v < 100 else f"{v:.1f} µs"


def cmd_report(args):
    peers = json.loads(Path(args.peers).read_text())
    res = peers["results"]
    crit = args.criterion
    print(f"CPU: {peers['cpu']}; numpy {peers['numpy']}, filterpy {peers['filterpy']}, "
          f"Python {peers['python']}")
    window = res["filterpy_ekf"]["steps_per_run"]
    step = criterion_us(crit, "ekf_step", "predict_range")
    step_w = criterion_us(crit, "ekf_window", "predict_range", str(window)) / window
    pred = criterion_us(crit, "ekf_predict", "predict")
    rows = [
        ("EKF step (predict + range update)", "8 states", "solsim one step", step,
         "filterpy ExtendedKalmanFilter", res["filterpy_ekf"]["median_us"]),
        ("EKF step (predict + range update)", "8 states", f"solsim, {window}-step window",
         step_w, "filterpy ExtendedKalmanFilter", res["filterpy_ekf"]["median_us"]),
        ("EKF step (predict + range update)", "8 states", f"solsim, {window}-step window",
         step_w, "numpy, same arithmetic", res["numpy_ekf"]["median_us"]),
        ("EKF predict", "8 states", "solsim one predict", pred,
         "filterpy set_step + predict", res["filterpy_ekf_predict"]["median_us"]),
    ]
    for n in COUNTS:
        ours = criterion_us(crit, "pf_resample", "systematic_indices", str(n))
        rows.append(("systematic resampling", f"N = {n}", "systematic_indices", ours,
                     "filterpy systematic_resample", res[f"filterpy_systematic/{n}"]["median_us"]))
        rows.append(("systematic resampling", f"N = {n}", "systematic_indices", ours,
                     "numpy searchsorted", res[f"numpy_systematic/{n}"]["median_us"]))
    for n in COUNTS:
        ours = criterion_us(crit, "pf_reweight", "update_with_scores", str(n))
        rows.append(("PF reweight + resample (no surface)", f"N = {n}", "update_with_scores",
                     ours, "numpy vectorised", res[f"numpy_reweight/{n}"]["median_us"]))
    print("ratio = peer / solsim (> 1: solsim faster)")
    print(f"| {'step':36s} | {'size':9s} | {'solsim':28s} | {'median':>10s} | {'peer':30s} | "
          f"{'median':>10s} | {'peer/solsim':>11s} |")
    for what, size, ours_name, ours, peer_name, peer in rows:
        print(f"| {what:36s} | {size:9s} | {ours_name:28s} | {fmt_us(ours):>10s} | "
              f"{peer_name:30s} | {fmt_us(peer):>10s} | {peer / ours:11.1f} |")
    print("\nPF update (census score surface + likelihood + grid resampling; no peer):")
    print(f"| {'N':5s} | {'thr':3s} | {'update':>10s} | {'score_surface alone':>19s} | "
          f"{'rest':>10s} | {'surface share':>13s} |")
    for threads in (1, 2):
        for n in COUNTS:
            upd = criterion_us(crit, "pf_update", f"n{n}", str(threads))
            surf = criterion_us(crit, "pf_update", f"score_surface_n{n}", str(threads))
            print(f"| {n:5d} | {threads:3d} | {fmt_us(upd):>10s} | {fmt_us(surf):>19s} | "
                  f"{fmt_us(upd - surf):>10s} | {100 * surf / upd:12.0f}% |")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
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
    main()
