"""Helpers shared by the peer benchmark scripts: the peers/.venv bootstrap, timing, CPU model."""
import os
import platform
import statistics
import subprocess
import sys
import time
from pathlib import Path

PEERS = Path(__file__).resolve().parent
VENV = PEERS / ".venv"


def ensure_venv(probe_imports):
    """Re-exec the running script inside peers/.venv, creating it and installing
    requirements.txt when `import <probe_imports>` fails there.

    The venv is shared by every peer script, so the packages are probed, not assumed.
    """
    if Path(sys.prefix).resolve() == VENV.resolve():
        return
    py = VENV / "bin" / "python"
    if not py.exists():
        subprocess.run([sys.executable, "-m", "venv", str(VENV)], check=True)
    probe = subprocess.run([str(py), "-c", f"import {probe_imports}"], capture_output=True)
    if probe.returncode != 0:
        print(f"installing {PEERS / 'requirements.txt'} into {VENV}", file=sys.stderr)
        subprocess.run([str(py), "-m", "pip", "install", "-q", "-r",
                        str(PEERS / "requirements.txt")], check=True, stdout=sys.stderr)
    os.execv(str(py), [str(py), str(Path(sys.argv[0]).resolve()), *sys.argv[1:]])


def timed(fn, runs):
    """(last result, stats in ms) of `runs` timed calls after one warm-up call."""
    result = fn()
    times = []
    for _ in range(runs):
        t0 = time.perf_counter()
        result = fn()
        times.append((time.perf_counter() - t0) * 1e3)
    return result, {"median_ms": statistics.median(times), "min_ms": min(times),
                    "max_ms": max(times), "runs": runs}


def cpu_model():
    """`lscpu`'s model name, else the platform's processor string."""
    try:
        out = subprocess.run(["lscpu"], capture_output=True, text=True, check=True).stdout
        for line in out.splitlines():
            if line.startswith("Model name"):
                return line.split(":", 1)[1].strip()
    except (OSError, subprocess.CalledProcessError):
        pass
    return platform.processor() or "unknown"
