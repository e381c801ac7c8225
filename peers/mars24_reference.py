#!/usr/bin/env python3
"""Independent reference for sim/src/mars_time.rs and sim/src/earth_time.rs: Mars time from the
`marstime` package, fed Terrestrial Time from ERFA (`pyerfa`).

Reads a JSON file written by tests/mars_time_mars24.rs:

    {"utc": [POSIX seconds or "YYYY-MM-DDTHH:MM:SS[.fff]Z", ...],
     "longitude_east_deg": float,      the mission's local-time longitude
     "landing_utc_s": float,           an instant in the landing sol (sol 0)
     "sclk_s": [float, ...],           Mars 2020 spacecraft clock readings
     "dates": [[year, month, day], ...]}

and writes to OUT.json (a file, not stdout: ~0.5 MB, more than a pipe holds while the test waits)

    {"versions": {"marstime": ..., "pyerfa": ..., "erfa": ...},
     "instants": [{"utc_s", "tai_minus_utc_s", "tt_minus_utc_s", "j2000_tt_days", "msd",
                   "mtc_h", "lmst_h", "local_msd", "sol"}, ...],      one per "utc", in order
     "sclk": [{"sclk_s", "utc_s", "utc", "in_leap_second"}, ...],    one per "sclk_s", in order
     "dat": [TAI - UTC at 00:00 UTC of each of "dates", ...],
     "leap_table": [[year, month, TAI - UTC], ...]}                   ERFA's table from 1972 on

every float at full precision (Python's repr).

How each figure is made, and what it shares with solsim (as little as the algorithm allows):

    time scales  ERFA, not marstime (whose own leap-second table stops at 2012, 35 s) and not
                 solsim's table: erfa.dtf2d("UTC", ...) -> erfa.utctai -> erfa.taitt gives the TT
                 Julian Date in two parts, and j2000_tt_days = (tt1 - 2451545.0) + tt2;
                 tai_minus_utc_s = erfa.dat(year, month, day, fraction of day), TT = TAI + 32.184 s.
    Mars time    marstime (Allison & McEwen 2000, the Mars24 recipe): Mars_Solar_Date,
                 Coordinated_Mars_Time, and Local_Mean_Solar_Time, which takes WEST longitude
                 (360 - east).
    mission sol  floor(local MSD) - floor(local MSD at landing), local MSD = MSD + east / 360 (the
                 mission's sols start at local mean midnight, the landing sol is sol 0).
    SCLK -> UTC  a Mars 2020 SCLK reading is TT seconds since J2000 (2000-01-01T12:00:00 TT):
                 erfa.tttai and erfa.taiutc on (2451545.0, sclk / 86400), then erfa.d2dtf for
                 the civil UTC: 23:59:60.x inside an inserted leap second ("in_leap_second"),
                 which POSIX seconds cannot name; "utc_s" then counts it as the next day's
                 00:00:00.x.

    peers/.venv/bin/python peers/mars24_reference.py IN.json OUT.json
    python3 peers/mars24_reference.py --versions     # print the package versions

Needs marstime and pyerfa (peers/requirements.txt). Run with another Python than peers/.venv's,
`ensure_venv` (peer_common.py) first creates peers/.venv or installs peers/requirements.txt there
when marstime or erfa does not import, then re-runs the script in it: `--versions` does just that
for a venv made before these two joined the requirements.
"""

import datetime
import json
import math
import re
import sys

from peer_common import ensure_venv

DAY_S = 86400.0
JD_J2000 = 2451545.0
TT_MINUS_TAI_S = 32.184
UNIX_EPOCH = datetime.date(1970, 1, 1)
ISO = re.compile(r"^(\d{4})-(\d{2})-(\d{2})T(\d{2}):(\d{2}):(\d{2}(?:\.\d+)?)Z$")


def civil_utc(value):
    """(year, month, day, hour, minute, second) of a POSIX time (float) or an ISO 8601 UTC string."""
    if isinstance(value, str):
        m = ISO.match(value)
        if m is None:
            raise ValueError(f"not YYYY-MM-DDTHH:MM:SS[.fff]Z: {value!r}")
        y, mo, d, h, mi = (int(m.group(i)) for i in range(1, 6))
        return y, mo, d, h, mi, float(m.group(6))
    days = math.floor(value / DAY_S)
    sec = value - days * DAY_S
    date = UNIX_EPOCH + datetime.timedelta(days=days)
    h = int(sec // 3600)
    mi = int((sec - 3600 * h) // 60)
    return date.year, date.month, date.day, h, mi, sec - 3600 * h - 60 * mi


def posix_s(y, mo, d, h, mi, s):
    """POSIX seconds of a civil UTC time (a 60th second runs into the next minute)."""
    days = (datetime.date(y, mo, d) - UNIX_EPOCH).days
    return days * DAY_S + h * 3600 + mi * 60 + s


def instant(value, lon_east_deg, sol_zero):
    import erfa
    import marstime

    y, mo, d, h, mi, s = civil_utc(value)
    u1, u2 = erfa.dtf2d("UTC", y, mo, d, h, mi, s)
    tt1, tt2 = erfa.taitt(*erfa.utctai(u1, u2))
    j2000_tt_days = (tt1 - JD_J2000) + tt2
    tai_minus_utc = float(erfa.dat(y, mo, d, (h * 3600 + mi * 60 + s) / DAY_S))
    msd = float(marstime.Mars_Solar_Date(j2000_tt_days))
    local_msd = msd + lon_east_deg / 360.0
    return {
        "utc_s": posix_s(y, mo, d, h, mi, s),
        "tai_minus_utc_s": tai_minus_utc,
        "tt_minus_utc_s": tai_minus_utc + TT_MINUS_TAI_S,
        "j2000_tt_days": j2000_tt_days,
        "msd": msd,
        "mtc_h": float(marstime.Coordinated_Mars_Time(j2000_tt_days)),
        "lmst_h": float(marstime.Local_Mean_Solar_Time(marstime.east_to_west(lon_east_deg),
                                                       j2000_tt_days)),
        "local_msd": local_msd,
        "sol": None if sol_zero is None else math.floor(local_msd) - sol_zero,
    }


def utc_of_sclk(sclk_s):
    import erfa

    u1, u2 = erfa.taiutc(*erfa.tttai(JD_J2000, sclk_s / DAY_S))
    y, mo, d, hmsf = erfa.d2dtf("UTC", 6, u1, u2)
    h, mi, s, f = (int(hmsf[k]) for k in ("h", "m", "s", "f"))
    y, mo, d = int(y), int(mo), int(d)
    return {
        "sclk_s": sclk_s,
        "utc_s": posix_s(y, mo, d, h, mi, s + f * 1e-6),
        "utc": f"{y:04d}-{mo:02d}-{d:02d}T{h:02d}:{mi:02d}:{s:02d}.{f:06d}Z",
        "in_leap_second": s == 60,
    }


def main():
    ensure_venv("marstime, erfa")
    import erfa
    from importlib.metadata import version

    versions = {"marstime": version("marstime"), "pyerfa": erfa.__version__,
                "erfa": erfa.version.erfa_version}
    if sys.argv[1:] == ["--versions"]:
        print(json.dumps(versions))
        return
    if len(sys.argv) != 3:
        sys.exit(f"usage: {sys.argv[0]} IN.json OUT.json | --versions")
    with open(sys.argv[1]) as f:
        request = json.load(f)
    lon = float(request["longitude_east_deg"])
    landing = instant(request["landing_utc_s"], lon, None)
    sol_zero = math.floor(landing["local_msd"])
    leap_table = [[int(r["year"]), int(r["month"]), float(r["tai_utc"])]
                  for r in erfa.leap_seconds.get() if int(r["year"]) >= 1972]
    out = {
        "versions": versions,
        "instants": [instant(v, lon, sol_zero) for v in request.get("utc", [])],
        "sclk": [utc_of_sclk(float(v)) for v in request.get("sclk_s", [])],
        "dat": [float(erfa.dat(y, m, d, 0.0)) for y, m, d in request.get("dates", [])],
        "leap_table": leap_table,
    }
    with open(sys.argv[2], "w") as f:
        json.dump(out, f)


if __name__ == "__main__":
    main()
