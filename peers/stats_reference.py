#!/usr/bin/env python3
"""Independent reference for sweep/src/stats.rs: statsmodels, numpy and scipy.

Reads the cases in peers/stats_fixtures/cases.json and computes, with the libraries a reviewer
would reach for:

    z          scipy.stats.norm.isf((1 - confidence) / 2)
    wilson     statsmodels.stats.proportion.proportion_confint(count, nobs,
               alpha=1 - confidence, method="wilson")
    quantile   numpy.quantile (default method "linear", Hyndman-Fan type 7), plus numpy.mean,
               numpy.median and the 5th / 95th percentiles that `stats::spread` reports
    bootstrap  scipy.stats.bootstrap((d,), numpy.mean, confidence_level=c, n_resamples=B,
               method="percentile", rng=numpy.random.default_rng(seed)); the same bootstrap
               distribution is then re-used for method="BCa" (given for information: solsim
               reports the percentile interval)

and prints the results as JSON on stdout, every float at full precision (Python's repr), in
exactly the bytes of the committed peers/stats_fixtures/expected.json:

    python3 peers/stats_reference.py                # print the JSON (sweep/tests/stats_reference.rs
                                                    # runs this and compares it to expected.json)
    python3 peers/stats_reference.py --write        # rewrite peers/stats_fixtures/expected.json
    python3 peers/stats_reference.py --make-cases   # rewrite cases.json from fixed seeds first

scipy's generator is not solsim's (ChaCha8), so the Rust test compares bootstrap endpoints within
their Monte Carlo error, and everything else within 1e-12.

The script needs numpy, scipy and statsmodels: `ensure_venv` (peer_common.py) creates peers/.venv
when needed, installs peers/requirements.txt there and re-runs itself with that interpreter.
"""

import argparse
import json
import sys
import warnings
from pathlib import Path

from peer_common import PEERS, ensure_venv

FIXTURES = PEERS / "stats_fixtures"
QUANTILE_LEVELS = [0.0, 0.01, 0.025, 0.05, 0.1, 0.25, 1 / 3, 0.5, 2 / 3, 0.75, 0.9, 0.95, 0.975,
                   0.99, 1.0]


def make_cases():
    """The fixture inputs. Continuous data are rounded to 4 decimals: per-run figures are, and
    such decimals parse exactly with serde_json's default (fast-path) float parser."""
    import numpy as np

    rng = np.random.default_rng(20260501)

    def rounded(values):
        return [round(float(v), 4) for v in values]

    def integers(choices, weights, size):
        return [float(v) for v in rng.choice(choices, p=weights, size=size)]

    z = [1e-6, 0.1, 0.5, 0.6826894921370859, 0.8, 0.9, 0.95, 0.9515, 0.95149, 0.9516, 0.98,
         0.99, 0.995, 0.999, 0.9999, 0.999999, 0.99999999, 0.9999999999]
    wilson = [(0, 10), (10, 10), (1, 1), (0, 1), (2, 40), (3, 20), (100, 200), (0, 200),
              (200, 200), (1, 1000), (999, 1000), (7, 13), (123456, 1000000)]
    wilson_cases = [{"successes": s, "n": n, "confidence": 0.95} for s, n in wilson]
    wilson_cases += [{"successes": s, "n": n, "confidence": c}
                     for c in (0.9, 0.99) for s, n in [(0, 1), (2, 40), (100, 200)]]
    quantile = [
        ("single", [5.0]),
        ("pair", [1.0, 2.0]),
        ("odd_unsorted", [3.0, 1.0, 4.0, 1.0, 5.0, 9.0, 2.0]),
        ("even_unsorted", [3.0, 1.0, 4.0, 1.0, 5.0, 9.0, 2.0, 6.0]),
        ("ties", [2.0, 2.0, 2.0, 3.0, 3.0, 7.0, 7.0, 7.0, 7.0]),
        ("negative_fractional", [-2.5, -0.1, 0.0, 0.3, 1.75, 10.0]),
        ("normal_n101", rounded(rng.normal(0.0, 1.0, 101))),
        ("sols_n200", integers([-3, -2, -1, 0, 1], [0.1, 0.25, 0.35, 0.25, 0.05], 200)),
    ]
    bootstrap = [
        ("sols_to_goal_n200",
         integers([-3, -2, -1, 0, 1], [0.1, 0.25, 0.35, 0.25, 0.05], 200)),
        ("rare_change_n200", integers([-1, 0, 1], [0.06, 0.9, 0.04], 200)),
        ("skewed_n200", rounded(rng.exponential(1.0, 200) - 1.0)),
        ("continuous_n1000", rounded(rng.normal(-1.9, 0.8, 1000))),
        ("constant_n100", [-0.7] * 100),
        ("two_values", [0.0, 1.0]),
        ("single", [2.5]),
    ]
    return {
        "z": z,
        "wilson": wilson_cases,
        "quantile": [{"name": name, "values": values, "p": QUANTILE_LEVELS}
                     for name, values in quantile],
        "bootstrap": [{"name": name, "differences": d, "n_resamples": 20000,
                       "confidence": 0.95, "seed": 1000 + i}
                      for i, (name, d) in enumerate(bootstrap)],
    }


def bootstrap_case(case):
    """Percentile (and, for information, BCa) interval of the mean; None where scipy declines
    (a single observation) or returns NaN (BCa on constant data)."""
    import numpy as np
    from scipy import stats

    d = np.asarray(case["differences"], dtype=np.float64)
    out = {"name": case["name"], "n": len(d), "mean": float(np.mean(d)),
           "sd": float(np.std(d)), "percentile": None, "standard_error": None, "bca": None}
    if len(d) < 2:
        return out
    res = stats.bootstrap((d,), np.mean, confidence_level=case["confidence"],
                          n_resamples=case["n_resamples"], method="percentile",
                          batch=1000, rng=np.random.default_rng(case["seed"]))
    ci = res.confidence_interval
    out["percentile"] = [float(ci.low), float(ci.high)]
    out["standard_error"] = float(res.standard_error)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        bca = stats.bootstrap((d,), np.mean, confidence_level=case["confidence"],
                              n_resamples=0, method="BCa", bootstrap_result=res,
                              rng=np.random.default_rng(case["seed"])).confidence_interval
    if np.isfinite(bca.low) and np.isfinite(bca.high):
        out["bca"] = [float(bca.low), float(bca.high)]
    return out


def reference(cases):
    import numpy as np
    import scipy
    import statsmodels
    from scipy import stats
    from statsmodels.stats.proportion import proportion_confint

    z = [{"confidence": c, "z": float(stats.norm.isf((1.0 - c) / 2.0))} for c in cases["z"]]
    wilson = []
    for case in cases["wilson"]:
        lo, hi = proportion_confint(case["successes"], case["n"], alpha=1.0 - case["confidence"],
                                    method="wilson")
        wilson.append({**case, "lo": float(lo), "hi": float(hi)})
    quantile = []
    for case in cases["quantile"]:
        v = np.asarray(case["values"], dtype=np.float64)
        quantile.append({
            "name": case["name"],
            "q": [float(q) for q in np.quantile(v, case["p"])],
            "mean": float(np.mean(v)),
            "median": float(np.median(v)),
            "p5": float(np.quantile(v, 0.05)),
            "p95": float(np.quantile(v, 0.95)),
        })
    return {
        "versions": {"numpy": np.__version__, "scipy": scipy.__version__,
                     "statsmodels": statsmodels.__version__},
        "z": z,
        "wilson": wilson,
        "quantile": quantile,
        "bootstrap": [bootstrap_case(case) for case in cases["bootstrap"]],
    }


def dumps(obj):
    return json.dumps(obj, indent=1) + "\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--write", action="store_true",
                    help="rewrite peers/stats_fixtures/expected.json instead of printing")
    ap.add_argument("--make-cases", action="store_true",
                    help="rewrite peers/stats_fixtures/cases.json from fixed seeds first")
    args = ap.parse_args()
    ensure_venv("numpy, scipy, statsmodels")

    cases_path = FIXTURES / "cases.json"
    if args.make_cases:
        FIXTURES.mkdir(exist_ok=True)
        cases_path.write_text(dumps(make_cases()), encoding="utf-8")
        print(f"wrote {cases_path}", file=sys.stderr)
    cases = json.loads(cases_path.read_text(encoding="utf-8"))
    text = dumps(reference(cases))
    if args.write:
        (FIXTURES / "expected.json").write_text(text, encoding="utf-8")
        print(f"wrote {FIXTURES / 'expected.json'}", file=sys.stderr)
    else:
        sys.stdout.write(text)


if __name__ == "__main__":
    main()
