#!/usr/bin/env python3
"""Peers for B1 (exact masked census Hamming scores at every offset, BENCHMARKS.md).

Loads the instance `cargo bench --bench localize` dumps with SOLSIM_CENSUS_DUMP=<dir>
(`template_codes.npy`, `template_valid.npy`, `map_codes.npy`, `map_valid.npy`, uint8 census
codes and per-bit validity; `census_checksum.json` = our sums of the mismatch and valid counts
over all offsets) and computes the same exact counts two ways:

- `scipy_fft_f64`: per census bit k, sign planes s (+1 valid and set, -1 valid and clear,
  0 invalid) and mask planes m; rfft2 in float64 (scipy.fft, fast padded size), conj(T)*M summed
  over the bits, two irfft2, rounded: valid = sum_k corr(mT, mM),
  mismatch = (valid - sum_k corr(sT, sM)) / 2. Timed with 1 and 2 scipy workers.
- `cv2_ccorr_f32`: 24 x cv2.matchTemplate(TM_CCORR) on float32 0/1 planes (per bit: valid,
  valid-and-set, valid-and-clear), each rounded to integers, then
  mismatch = valid - agree_set - agree_clear. Timed with cv2.setNumThreads(1) and (2).

- `pipeline_cv2`: the B2 peer, timed end to end on seeded inputs of B2's sizes: numpy census
  transforms of a 480^2 window and a 240^2 orthomosaic (5 % holes + 30 % wedge), the exact
  counts by the 24 x TM_CCORR above, a masked cv2 TM_SQDIFF DEM term (60^2 over 122^2 at 1 m),
  the scores combined on the 25 cm offsets, argmin and a 3x3 quadratic sub-pixel fit. Timed with
  cv2.setNumThreads(1) and (2); it must find the planted offset (137, 94).

Both census variants must reproduce our sums exactly (the script exits non-zero otherwise). Each variant is
timed after one warm-up, >= 5 runs; median, min and max in ms.

Usage:
  peers/bench_census.py peers  --dump DIR [--runs N] [--out peers.json]
  peers/bench_census.py report --peers peers.json --criterion target/bench-native/criterion

`peers` re-runs itself inside peers/.venv, creating it from peers/requirements.txt if needed.
"""
import argparse
import json
import sys
from pathlib import Path

from peer_common import cpu_model, ensure_venv, timed

PEERS = Path(__file__).resolve().parent


def planes(codes, valid, k, np):
    v = ((valid >> k) & 1).astype(np.float64)
    c = ((codes >> k) & 1).astype(np.float64)
    return v * (2.0 * c - 1.0), v


def scores_scipy(t_codes, t_valid, m_codes, m_valid, workers):
    import numpy as np
    import scipy.fft as sf
    th, tw = t_codes.shape
    mh, mw = m_codes.shape
    oh, ow = mh - th + 1, mw - tw + 1
    shape = (sf.next_fast_len(mh, real=True), sf.next_fast_len(mw, real=True))
    acc_s = acc_m = None
    for k in range(8):
        ts, tm = planes(t_codes, t_valid, k, np)
        ms, mm = planes(m_codes, m_valid, k, np)
        fs = np.conj(sf.rfft2(ts, shape, workers=workers)) * sf.rfft2(ms, shape, workers=workers)
        fm = np.conj(sf.rfft2(tm, shape, workers=workers)) * sf.rfft2(mm, shape, workers=workers)
        acc_s = fs if acc_s is None else acc_s + fs
        acc_m = fm if acc_m is None else acc_m + fm
    s = np.rint(sf.irfft2(acc_s, shape, workers=workers)[:oh, :ow]).astype(np.int64)
    valid = np.rint(sf.irfft2(acc_m, shape, workers=workers)[:oh, :ow]).astype(np.int64)
    return (valid - s) // 2, valid


def scores_cv2(t_codes, t_valid, m_codes, m_valid):
    import cv2
    import numpy as np
    valid = agree = 0
    for k in range(8):
        tv = ((t_valid >> k) & 1).astype(np.float32)
        mv = ((m_valid >> k) & 1).astype(np.float32)
        tc = ((t_codes >> k) & 1).astype(np.float32)
        mc = ((m_codes >> k) & 1).astype(np.float32)
        for a, b in ((tv, mv), (tc * tv, mc * mv), ((1 - tc) * tv, (1 - mc) * mv)):
            r = np.rint(cv2.matchTemplate(b, a, cv2.TM_CCORR)).astype(np.int64)
            if a is tv:
                valid = valid + r
            else:
                agree = agree + r
    return valid - agree, valid


def census_np(img, valid):
    """numpy census transform: 8 code bits (centre > neighbour) and 8 validity bits per pixel,
    neighbours in solsim's order (NW, N, NE, W, E, SW, S, SE); outside the image is invalid."""
    import numpy as np
    h, w = img.shape
    p = np.zeros((h + 2, w + 2), np.uint8)
    p[1:-1, 1:-1] = img
    ok = np.zeros((h + 2, w + 2), np.uint8)
    ok[1:-1, 1:-1] = valid
    codes = np.zeros((h, w), np.uint8)
    vbits = np.zeros((h, w), np.uint8)
    c, vc = p[1:-1, 1:-1], ok[1:-1, 1:-1]
    for k, (dc, dr) in enumerate(((-1, -1), (0, -1), (1, -1), (-1, 0), (1, 0), (-1, 1), (0, 1),
                                  (1, 1))):
        nb = p[1 + dr:h + 1 + dr, 1 + dc:w + 1 + dc]
        vn = ok[1 + dr:h + 1 + dr, 1 + dc:w + 1 + dc]
        both = vc & vn
        vbits |= both << k
        codes |= ((c > nb) & both).astype(np.uint8) << k
    return codes, vbits


def pipeline_instance():
    """Seeded inputs of B2's sizes: a 480^2 appearance window (all valid), a 240^2 orthomosaic
    with 5 % holes + the 30 % rear wedge, a 60^2 rover DEM over a 122^2 orbital DEM window."""
    import numpy as np
    rng = np.random.default_rng(2026)
    window = rng.integers(0, 256, (480, 480), dtype=np.uint8)
    ortho = window[94:334, 137:377].copy()
    y, x = np.mgrid[0:240, 0:240] - 119.5
    turns = np.abs(np.arctan2(x, y)) / (2 * np.pi)
    valid = ~((rng.random((240, 240)) < 0.05) | (turns < 0.15))
    dem_map = rng.normal(0, 2, (122, 122)).astype(np.float32)
    dem_rover = dem_map[33:93, 21:81] + 3.0
    dem_mask = np.ones((60, 60), np.float32)
    return window, ortho, valid, dem_map, dem_rover, dem_mask


def pipeline_cv2(inst):
    """The B2 peer pipeline: 2 numpy census transforms, the exact counts by 24 x cv2 TM_CCORR,
    the masked cv2 TM_SQDIFF DEM term (60^2 over 122^2), scores combined on the census offsets,
    argmin and the 3x3 quadratic sub-pixel fit."""
    import cv2
    import numpy as np
    window, ortho, valid, dem_map, dem_rover, dem_mask = inst
    m_codes, m_valid = census_np(window, np.ones_like(window, dtype=np.uint8))
    t_codes, t_valid = census_np(ortho, valid.astype(np.uint8))
    mis, val = scores_cv2(t_codes, t_valid, m_codes, m_valid)
    score = mis / np.maximum(val, 1)
    dem = cv2.matchTemplate(dem_map, dem_rover, cv2.TM_SQDIFF, mask=dem_mask)
    dem = dem / (dem + 0.09 * 3600)
    # DEM offsets are 1 m, census offsets 25 cm: nearest DEM offset for each census offset.
    iy = np.minimum(np.arange(score.shape[0]) // 4, dem.shape[0] - 1)
    ix = np.minimum(np.arange(score.shape[1]) // 4, dem.shape[1] - 1)
    combined = score + 0.3 * dem[np.ix_(iy, ix)]
    by, bx = np.unravel_index(np.argmin(combined), combined.shape)
    by, bx = min(max(by, 1), combined.shape[0] - 2), min(max(bx, 1), combined.shape[1] - 2)
    z = combined[by - 1:by + 2, bx - 1:bx + 2]
    gx = (z[:, 2] - z[:, 0]).sum() / 6
    gy = (z[2, :] - z[0, :]).sum() / 6
    hxx = (z[:, 0] - 2 * z[:, 1] + z[:, 2]).sum() / 3
    hyy = (z[0, :] - 2 * z[1, :] + z[2, :]).sum() / 3
    return bx - gx / max(hxx, 1e-12), by - gy / max(hyy, 1e-12)


def cmd_peers(args):
    ensure_venv("cv2, numpy, scipy")
    import cv2
    import numpy as np
    import scipy
    d = Path(args.dump)
    t_codes, t_valid, m_codes, m_valid = (np.load(d / f"{n}.npy") for n in (
        "template_codes", "template_valid", "map_codes", "map_valid"))
    ours = json.loads((d / "census_checksum.json").read_text())
    want = (ours["mismatch_sum"], ours["valid_sum"])
    results = {}
    ok = True
    variants = [(f"scipy_fft_f64/{w}", lambda w=w: scores_scipy(t_codes, t_valid, m_codes,
                                                              m_valid, w)) for w in (1, 2)]
    for n in (1, 2):
        def run(n=n):
            cv2.setNumThreads(n)
            return scores_cv2(t_codes, t_valid, m_codes, m_valid)
        variants.append((f"cv2_ccorr_f32/{n}", run))
    for name, fn in variants:
        (mis, val), stats = timed(fn, args.runs)
        sums = (int(mis.sum()), int(val.sum()))
        stats["checksum_ok"] = sums == want
        stats["shape"] = list(mis.shape)
        ok &= stats["checksum_ok"]
        results[name] = stats
        print(f"{name:18s} median {stats['median_ms']:8.1f} ms  (min {stats['min_ms']:.1f}, "
              f"max {stats['max_ms']:.1f}, {args.runs} runs)  sums {sums} "
              f"{'== ours' if stats['checksum_ok'] else '!= ours ' + str(want)}")
    inst = pipeline_instance()
    for n in (1, 2):
        def run(n=n):
            cv2.setNumThreads(n)
            return pipeline_cv2(inst)
        (px, py), stats = timed(run, args.runs)
        stats["subpixel_offset"] = [float(px), float(py)]
        results[f"pipeline_cv2/{n}"] = stats
        print(f"{'pipeline_cv2/' + str(n):18s} median {stats['median_ms']:8.1f} ms  (min "
              f"{stats['min_ms']:.1f}, max {stats['max_ms']:.1f}, {args.runs} runs)  best offset "
              f"({px:.3f}, {py:.3f}), planted (137, 94)")
    out = {"cpu": cpu_model(), "numpy": np.__version__, "scipy": scipy.__version__,
           "opencv": cv2.__version__, "results": results}
    if args.out:
        Path(args.out).write_text(json.dumps(out, indent=1))
    if not ok:
        sys.exit("census peers: checksum mismatch")


def criterion_ms(root, group, bench, threads):
    p = Path(root) / group / bench / str(threads) / "new" / "estimates.json"
    est = json.loads(p.read_text())
    return est["median"]["point_estimate"] / 1e6


def cmd_report(args):
    peers = json.loads(Path(args.peers).read_text())
    res = peers["results"]
    print(f"CPU: {peers['cpu']}")
    print(f"{'ours':14s} {'thr':>3s} {'ours ms':>9s} {'cv2 ms':>8s} {'ours/cv2':>9s} "
          f"{'scipy ms':>9s} {'ours/scipy':>10s}")
    for bench in ("fft", "brute"):
        for n in (1, 2):
            ours = criterion_ms(args.criterion, "census_b1", bench, n)
            cv = res[f"cv2_ccorr_f32/{n}"]["median_ms"]
            sp = res[f"scipy_fft_f64/{n}"]["median_ms"]
            print(f"B1 {bench:10s} {n:3d} {ours:9.1f} {cv:8.1f} {ours / cv:9.2f} {sp:9.1f} "
                  f"{ours / sp:10.2f}")
    for n in (1, 2):
        ours = criterion_ms(args.criterion, "localize_b2", "localize", n)
        # The whole cv2/numpy pipeline, timed end to end in this job (pipeline_cv2), with the
        # same thread count.
        pipeline = res[f"pipeline_cv2/{n}"]["median_ms"]
        print(f"B2 localize    {n:3d} {ours:9.1f}  peer pipeline {pipeline:.1f} ms "
              f"(ours/peer {ours / pipeline:.2f}); target 20 ms: "
              f"{'met' if ours < 20.0 else 'NOT met'}")


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
