#!/usr/bin/env python3
"""Independent reference for localization/src/ekf: the same EKF run by filterpy.

Reads a JSON file written by tests/ekf_filterpy.rs -- the navigation frame (site, Mars rotation),
the filter's x0, P0, Q and measurement variances, and the IMU, range and fix streams of one run
-- and runs filterpy's ExtendedKalmanFilter over them:

    predict   filterpy's predict() is linear (x = F x + B u), so predict_x is overridden with an
              RK4 step of the rover model (written again here from paper 004 eq. 2, not read from
              the Rust code); F is set beforehand to the transition matrix I + F dt + (F dt)^2/2 +
              (F dt)^3/6 of the Jacobian at the step's start, so predict() gives P = F P F' + Q.
    update    ExtendedKalmanFilter.update(z, HJacobian, Hx, R): the range (eq. 8, rover position
              on the rotating sphere carried to the Mars-centred inertial frame) and then the
              terrain-matching fix (H = [I 0]) of each second. filterpy updates P in Joseph form.

and writes {"filterpy": version, "steps": [{"t_s", "x", "P"}, ...]} (after each second's updates;
t = 0 first) as JSON to OUT.json, every float at full precision (a file, not stdout: ~1 MB per run):

    peers/.venv/bin/python peers/ekf_filterpy.py RUN.json OUT.json

Needs numpy and filterpy (peers/requirements.txt).
"""

import json
import sys

import numpy as np
from filterpy.kalman import ExtendedKalmanFilter

EAST, NORTH, VE, VN, HEADING, BAX, BAY, BG = range(8)


class Frame:
    """East-north-up tangent plane at a site on a sphere turning about the MCI z axis."""

    def __init__(self, f):
        lat, lon = np.radians(f["latitude_deg"]), np.radians(f["longitude_deg"])
        self.east = np.array([-np.sin(lon), np.cos(lon), 0.0])
        self.north = np.array([-np.sin(lat) * np.cos(lon), -np.sin(lat) * np.sin(lon), np.cos(lat)])
        self.site = f["radius_m"] * np.array(
            [np.cos(lat) * np.cos(lon), np.cos(lat) * np.sin(lon), np.sin(lat)])
        self.rate = f["rotation_rad_per_s"]
        self.theta0 = f["prime_meridian_at_epoch_rad"]

    def rot(self, t):
        c, s = np.cos(self.theta0 + self.rate * t), np.sin(self.theta0 + self.rate * t)
        return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])

    def rover_mci(self, t, e, n):
        return self.rot(t) @ (self.site + e * self.east + n * self.north)


def derivative(x, accel_xy, yaw_rate):
    c, s = np.cos(x[HEADING, 0]), np.sin(x[HEADING, 0])
    ax, ay = accel_xy[0] - x[BAX, 0], accel_xy[1] - x[BAY, 0]
    d = np.zeros((8, 1))
    d[EAST, 0], d[NORTH, 0] = x[VE, 0], x[VN, 0]
    d[VE, 0] = c * ax - s * ay
    d[VN, 0] = s * ax + c * ay
    d[HEADING, 0] = yaw_rate - x[BG, 0]
    return d


def jacobian(x, accel_xy):
    c, s = np.cos(x[HEADING, 0]), np.sin(x[HEADING, 0])
    ax, ay = accel_xy[0] - x[BAX, 0], accel_xy[1] - x[BAY, 0]
    f = np.zeros((8, 8))
    f[EAST, VE] = f[NORTH, VN] = 1.0
    f[VE, HEADING] = -s * ax - c * ay
    f[VN, HEADING] = c * ax - s * ay
    f[VE, BAX], f[VE, BAY] = -c, s
    f[VN, BAX], f[VN, BAY] = -s, -c
    f[HEADING, BG] = -1.0
    return f


class RoverEKF(ExtendedKalmanFilter):
    """filterpy's EKF with the rover's nonlinear RK4 propagation as predict_x."""

    def set_step(self, u0, u1, dt):
        self.u0, self.u1, self.dt = u0, u1, dt
        a_mean = 0.5 * (np.asarray(u0["accel"][:2]) + np.asarray(u1["accel"][:2]))
        fdt = jacobian(self.x, a_mean) * dt
        self.F = np.eye(8) + fdt + fdt @ fdt / 2.0 + fdt @ fdt @ fdt / 6.0

    def predict_x(self, u=0):
        a0, a1 = np.asarray(self.u0["accel"][:2]), np.asarray(self.u1["accel"][:2])
        w0, w1 = self.u0["yaw_rate"], self.u1["yaw_rate"]
        am, wm, h = 0.5 * (a0 + a1), 0.5 * (w0 + w1), self.dt
        x = self.x
        k1 = derivative(x, a0, w0)
        k2 = derivative(x + 0.5 * h * k1, am, wm)
        k3 = derivative(x + 0.5 * h * k2, am, wm)
        k4 = derivative(x + h * k3, a1, w1)
        self.x = x + h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4)


def main():
    run = json.load(open(sys.argv[1]))
    frame = Frame(run["frame"])

    def range_h(x, t, r_o):
        return np.array([[np.linalg.norm(frame.rover_mci(t, x[EAST, 0], x[NORTH, 0]) - r_o)]])

    def range_jac(x, t, r_o):
        d = frame.rover_mci(t, x[EAST, 0], x[NORTH, 0]) - r_o
        u = d / np.linalg.norm(d)
        rot = frame.rot(t)
        h = np.zeros((1, 8))
        h[0, EAST], h[0, NORTH] = u @ (rot @ frame.east), u @ (rot @ frame.north)
        return h

    def fix_h(x):
        return x[[EAST, NORTH], :]

    def fix_jac(x):
        h = np.zeros((2, 8))
        h[0, EAST] = h[1, NORTH] = 1.0
        return h

    ekf = RoverEKF(dim_x=8, dim_z=1)
    ekf.x = np.asarray(run["x0"], float).reshape(8, 1)
    ekf.P = np.asarray(run["P0"], float)
    ekf.Q = np.asarray(run["Q"], float)
    r_range = np.array([[run["range_variance_m2"]]])
    r_fix = np.eye(2) * run["fix_variance_m2"]
    ranges = {r["t_s"]: r for r in run["ranges"]}
    fixes = {f["t_s"]: f for f in run["fixes"]}

    def snapshot(t):
        return {"t_s": t, "x": ekf.x[:, 0].tolist(), "P": ekf.P.tolist()}

    imu = run["imu"]
    steps = [snapshot(imu[0]["t_s"])]
    for u0, u1 in zip(imu, imu[1:]):
        t = u1["t_s"]
        ekf.set_step(u0, u1, float(t - u0["t_s"]))
        ekf.predict()
        if t in ranges:
            r_o = np.asarray(ranges[t]["orbiter_mci_m"], float)
            ekf.update(np.array([[ranges[t]["range_m"]]]), range_jac, range_h, R=r_range,
                       args=(float(t), r_o), hx_args=(float(t), r_o))
        if t in fixes:
            ekf.update(np.asarray(fixes[t]["enu_m"], float).reshape(2, 1), fix_jac, fix_h, R=r_fix)
        steps.append(snapshot(t))
    with open(sys.argv[2], "w") as out:
        json.dump({"filterpy": __import__("filterpy").__version__, "steps": steps}, out)


if __name__ == "__main__":
    main()
