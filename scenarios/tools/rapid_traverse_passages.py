#!/usr/bin/env python3
"""Add the narrow passages of the rapid-traverse map to its zones file (a modelling choice): the
conjunction scenario's zones (the rapid traverse itself is rebuilt from the record since issue 27).

Paper 000 §8: "if the rover needed to navigate through a narrow region, that had to occur early
in the drive when the uncertainty remained small enough to enable threading the needle." The
record of sols 379-409 has no fault, so wherever the historic planners met a narrow passage the
rover met it early in a sol. The rule used here, applied once to a replay on the map *without*
passages (`solsim run scenarios/rapid-traverse-379-409.toml --strategy replay --json`, seed
379, at commit 429557f with this file's passages removed):

  walking the route from 400 m, place a passage at the first point such that the replay's
  radius stays at most 9 m from the start of the point's route leg to 25 m past the point
  (AutoNav plans to the next waypoint, so a passage closes for the whole leg before it), and
  that lies at least 60 m from every other keep-out; then move on 600 m and repeat, up to where
  the record ends (5108 m).

That gives the four route positions below (metres along the route from waypoint 0). Each passage
is a pair of keep-out ridges 20 m thick across the strategic corridor, leaving a gap of
2 × 18.5 m centred on the route: with the 1.5 m footprint, a clearance of about 17 m. 17 m lies
between one sol's growth at the calibrated 222 m per drive sol (≈ 11 m at 5 %, ≈ 13.5 m after
an onboard localization's 1.93 m) and two sols' (≈ 22 m): the passages close on the second sol
without a localization, as sol 385's did (paper 000 Fig. 4, 23.5 m).

Usage: python3 scenarios/tools/rapid_traverse_passages.py scenarios/conjunction.zones.geojson
(rewrites the file in place; idempotent: earlier passage ridges are replaced).
"""
import json
import math
import sys
import tomllib
from pathlib import Path

ALONG_M = [610, 1510, 3010, 3930]
HALF_GAP_M = 18.5
RIDGE_LENGTH_M = 20.0
CORRIDOR_Y = (700.0, 1300.0)  # beyond the keep-in corridor (780-1210 m)


def main(zones_path: Path) -> None:
    scenario = tomllib.loads(
        (zones_path.parent / "conjunction.toml").read_text())
    route = scenario["route"]["waypoints"]
    along = [0.0]
    for a, b in zip(route, route[1:]):
        along.append(along[-1] + math.dist(a, b))
    zones = json.loads(zones_path.read_text())
    zones["features"] = [
        f for f in zones["features"] if not f["properties"]["name"].startswith("passage ")
    ]
    for n, s in enumerate(ALONG_M, start=1):
        i = next(k for k in range(1, len(route)) if along[k] >= s)
        t = (s - along[i - 1]) / (along[i] - along[i - 1])
        x = route[i - 1][0] + t * (route[i][0] - route[i - 1][0])
        y = route[i - 1][1] + t * (route[i][1] - route[i - 1][1])
        x0, x1 = round(x - RIDGE_LENGTH_M / 2, 1), round(x + RIDGE_LENGTH_M / 2, 1)
        for side, (y0, y1) in (
            ("north", (round(y + HALF_GAP_M, 1), CORRIDOR_Y[1])),
            ("south", (CORRIDOR_Y[0], round(y - HALF_GAP_M, 1))),
        ):
            zones["features"].append({
                "type": "Feature",
                "properties": {
                    "kind": "keep_out",
                    "name": f"passage {n} {side} ridge ({s} m along the route)",
                },
                "geometry": {
                    "type": "Polygon",
                    "coordinates": [[[x0, y0], [x1, y0], [x1, y1], [x0, y1], [x0, y0]]],
                },
            })
    zones_path.write_text(json.dumps(zones, indent=1) + "\n")


if __name__ == "__main__":
    main(Path(sys.argv[1]))
