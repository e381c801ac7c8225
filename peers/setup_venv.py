"""Creates peers/.venv with every package in peers/requirements.txt (from PyPI), or brings an
existing one up to date: the Python half of the external checks that `scripts/test.sh` runs.

    python3 peers/setup_venv.py

Prints the packages the tests import and their versions. Needs python3 with the venv module
(Debian: python3-venv) and a reachable PyPI.
"""
import importlib.metadata
import sys
from pathlib import Path

from peer_common import ensure_venv

# Every module a test or a peer script imports from the venv (requirements.txt's packages).
MODULES = ["numpy", "scipy", "cv2", "pyastar2d", "shapely", "ortools", "statsmodels", "pyarrow",
           "jsonschema", "filterpy", "marstime", "erfa"]


def main():
    ensure_venv(", ".join(MODULES))
    for line in (Path(__file__).parent / "requirements.txt").read_text().splitlines():
        if line.strip() and not line.startswith("#"):
            dist, _, pinned = line.partition("==")
            print(f"{dist} {importlib.metadata.version(dist)} (pinned {pinned})")
    print(f"peers/.venv ready: {sys.prefix}")


if __name__ == "__main__":
    main()
