#!/usr/bin/env python3
"""Independent reference for `solsim zones check`, computed with shapely (GEOS).

Reads a zones GeoJSON FeatureCollection (Polygon / MultiPolygon features with a `kind` property,
"keep_in" or "keep_out", and an optional `name`) and a points CSV (header row; columns `x_m`,
`y_m` and optionally `name`, in any order), and prints for every point:

    keep_out_distance_m      distance to the union of keep-out zones (0 inside); inf if none
    keep_in_edge_distance_m  union.boundary.distance(p) if the keep-in union contains p, else 0;
                             inf if there are no keep-ins
    max_uncertainty_m        min(the two) - footprint radius

as the fixed-width table `solsim zones check` prints (3 decimals; without its status column and
the line under it), or with `--csv` as CSV at full precision (repr of each float), which is how
zones_fixtures/expected_shapely.csv is made:

    python3 peers/zones_reference.py peers/zones_fixtures/zones.geojson \\
        peers/zones_fixtures/points.csv --footprint-radius-m 0.75 --csv \\
        > peers/zones_fixtures/expected_shapely.csv

`--make-points OUT` rewrites the fixture points (hand-picked cases plus 200 seeded random points).

The script needs shapely 2; if it is missing it creates peers/.venv (python3 -m venv), installs
`shapely==2.*` from PyPI there and re-runs itself with that interpreter.
"""

import argparse
import csv
import json
import math
import os
import random
import subprocess
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
VENV = HERE / ".venv"
COLUMNS = ["name", "x_m", "y_m", "keep_out_distance_m", "keep_in_edge_distance_m", "max_uncertainty_m"]


def ensure_shapely():
    """Import shapely, or create the venv, install it there and re-execute inside it."""
    try:
        import shapely  # noqa: F401

        return
    except ImportError:
        pass
    python = VENV / "bin" / "python"
    if Path(sys.prefix).resolve() == VENV.resolve():
        sys.exit(f"shapely is not installed in {VENV}; run: {python} -m pip install 'shapely==2.*'")
    if not python.exists():
        print(f"creating {VENV}", file=sys.stderr)
        subprocess.check_call([sys.executable, "-m", "venv", str(VENV)])
    probe = subprocess.run([str(python), "-c", "import shapely"], capture_output=True)
    if probe.returncode != 0:
        print("installing shapely==2.* into the venv", file=sys.stderr)
        subprocess.check_call(
            [str(python), "-m", "pip", "install", "--quiet", "shapely==2.*"], stdout=sys.stderr
        )
    os.execv(str(python), [str(python), str(Path(__file__).resolve()), *sys.argv[1:]])


def normalise_kind(value):
    """keep_in / keep_out, ignoring case, '-', '_' and spaces (as the Rust reader does)."""
    if not isinstance(value, str):
        return None
    squeezed = "".join(c for c in value.lower() if c not in "-_ ")
    return {"keepin": "keep_in", "keepout": "keep_out"}.get(squeezed)


def read_zones(path):
    from shapely.geometry import shape

    with open(path, encoding="utf-8") as f:
        collection = json.load(f)
    if collection.get("type") != "FeatureCollection":
        sys.exit(f"{path}: expected a FeatureCollection")
    zones = {"keep_in": [], "keep_out": []}
    for i, feature in enumerate(collection["features"]):
        props = feature.get("properties") or {}
        kind = normalise_kind(props.get("kind"))
        if kind is None:
            sys.exit(f"{path}: features[{i}].properties.kind: expected keep_in or keep_out")
        geometry = shape(feature["geometry"])
        if geometry.geom_type not in ("Polygon", "MultiPolygon") or not geometry.is_valid:
            sys.exit(f"{path}: features[{i}].geometry: expected a valid Polygon or MultiPolygon")
        zones[kind].append(geometry)
    return zones


def read_points(path):
    with open(path, newline="", encoding="utf-8") as f:
        reader = csv.DictReader(f)
        extra = set(reader.fieldnames or []) - {"name", "x_m", "y_m"}
        if extra or not {"x_m", "y_m"} <= set(reader.fieldnames or []):
            sys.exit(f"{path}: expected columns x_m,y_m[,name], got {reader.fieldnames}")
        points = []
        for k, row in enumerate(reader):
            name = row.get("name") or f"point-{k}"
            points.append((name, float(row["x_m"]), float(row["y_m"])))
    return points


def compute(zones, points, footprint_radius_m):
    from shapely import unary_union
    from shapely.geometry import Point

    keep_out = unary_union(zones["keep_out"]) if zones["keep_out"] else None
    keep_in = unary_union(zones["keep_in"]) if zones["keep_in"] else None
    keep_in_edge = keep_in.boundary if keep_in is not None else None
    rows = []
    for name, x, y in points:
        p = Point(x, y)
        d_out = keep_out.distance(p) if keep_out is not None else math.inf
        if keep_in is None:
            d_in = math.inf
        elif keep_in.contains(p):
            d_in = keep_in_edge.distance(p)
        else:
            d_in = 0.0
        rows.append((name, x, y, d_out, d_in, min(d_out, d_in) - footprint_radius_m))
    return rows


def print_table(rows, out):
    """The fixed-width table of `solsim zones check`: name left-aligned, numbers right-aligned."""
    cells = [[r[0]] + [f"{v:.3f}" for v in r[1:]] for r in rows]
    widths = [max([len(c)] + [len(row[i]) for row in cells]) for i, c in enumerate(COLUMNS)]

    def line(values):
        parts = [values[0].ljust(widths[0])] + [v.rjust(w) for v, w in zip(values[1:], widths[1:])]
        return "  ".join(parts)

    out.write(line(COLUMNS) + "\n")
    for row in cells:
        out.write(line(row) + "\n")


def print_csv(rows, out):
    writer = csv.writer(out, lineterminator="\n")
    writer.writerow(COLUMNS)
    for name, *values in rows:
        writer.writerow([name] + [repr(float(v)) for v in values])


def make_points(path):
    """Hand-picked cases (edges, vertices, holes, overlaps, abutting keep-ins) plus random points."""
    cases = [
        ("L notch", 130, 140),  # inside the L's concave corner: 15 m from x = 115
        ("L inside", 105, 150),
        ("L vertex", 100, 100),
        ("L edge", 130, 100),
        ("L reentrant vertex", 115, 115),
        ("spur overlap", 150, 105),  # in both the L and the dune spur
        ("C mouth", 300, 135),  # between the C's arms: 17 m from both
        ("C inner corner", 268, 118),
        ("mesa hole centre", 420, 80),  # inside a hole: outside the keep-out
        ("mesa hole edge", 400, 80),
        ("mesa triangle hole", 450.25, 108),
        ("mesa rim", 390, 50),
        ("boulder hole", 165, 315),
        ("boulder gap", 205, 258),
        ("main vertex", 20, 20),
        ("main edge", 190, 15),
        ("main east overlap", 350, 100),  # in both work areas
        ("east inner edge", 335, 105),  # on work area east's west edge, inside work area main
        ("shared pad edge", 492, 88),  # on the edge work area east shares with east pad
        ("pad", 520, 90),
        ("corridor hole", 200, 300),  # in the corridor's hole: outside every keep-in
        ("corridor hole edge", 225, 280),
        ("patched hole", 250, 310),  # in the hole but inside the hole patch
        ("corridor over main", 250, 205),
        ("multipart touch", 60, 380),  # where the two parts of zone-10 touch
        ("multipart west", 0, 340),
        ("far away", 600, 450),
        ("far south", 250, -40),
    ]
    rng = random.Random(20261122)
    for k in range(200):
        cases.append((f"random-{k:03}", round(rng.uniform(-30, 570), 3), round(rng.uniform(-30, 440), 3)))
    with open(path, "w", newline="", encoding="utf-8") as f:
        writer = csv.writer(f, lineterminator="\n")
        writer.writerow(["name", "x_m", "y_m"])
        for name, x, y in cases:
            writer.writerow([name, x, y])


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("zones", nargs="?", help="zones GeoJSON FeatureCollection")
    parser.add_argument("points", nargs="?", help="points CSV with columns x_m,y_m[,name]")
    parser.add_argument("--footprint-radius-m", type=float, default=0.0)
    parser.add_argument("--csv", action="store_true", help="full-precision CSV instead of the table")
    parser.add_argument("--make-points", metavar="OUT", help="write the fixture points CSV and exit")
    args = parser.parse_args()
    if args.make_points:
        make_points(args.make_points)
        return
    if not (args.zones and args.points):
        parser.error("ZONES and POINTS are required")
    ensure_shapely()
    rows = compute(read_zones(args.zones), read_points(args.points), args.footprint_radius_m)
    (print_csv if args.csv else print_table)(rows, sys.stdout)


if __name__ == "__main__":
    main()
