#!/usr/bin/env bash
# The whole test suite: solsim's own tests and the external checks that compare it with tools it
# does not build (shapely, statsmodels, pyarrow, jsonschema, OR-Tools CP-SAT, filterpy and marstime
# in peers/.venv; Chromium; GDAL; groff; util-linux's `script`; a real Slurm cluster, as root).
#
#   scripts/test.sh                    create what the external checks need, then run everything
#   scripts/test.sh --skip-external    run without what is missing; the last lines count it
#   scripts/test.sh -- ARGS            pass ARGS to `cargo test --workspace` (e.g. a test filter)
#
# Without --skip-external it creates peers/.venv from PyPI (python3 peers/setup_venv.py) and, run
# as root, installs the Debian packages (apt-get). Otherwise it stops before building, naming what
# is missing and the command that installs it. No check passes without having run: a test that
# lacks its tool fails, unless this opt-out is given, and then it is counted here.
set -euo pipefail
cd "$(dirname "$0")/.."

usage() { sed -n '2,13s/^# \{0,1\}//p' "$0"; }

skip_external=false
cargo_args=()
while [ $# -gt 0 ]; do
    case "$1" in
        --skip-external) skip_external=true ;;
        -h | --help) usage; exit 0 ;;
        --) shift; cargo_args=("$@"); break ;;
        *) echo "scripts/test.sh: unknown argument '$1' (expected --skip-external, --help or -- CARGO_TEST_ARGS)" >&2; exit 2 ;;
    esac
    shift
done

# Debian package -> the program the tests run from it.
packages=(chromium gdal-bin groff-base util-linux)
programs=(chromium ogrinfo groff script)
missing_packages=()
for i in "${!packages[@]}"; do
    command -v "${programs[$i]}" > /dev/null || missing_packages+=("${packages[$i]}")
done
is_root=false
[ "$(id -u)" = 0 ] && is_root=true

if ! $skip_external; then
    problems=()
    if [ ${#missing_packages[@]} -gt 0 ]; then
        if $is_root && command -v apt-get > /dev/null; then
            echo "scripts/test.sh: installing ${missing_packages[*]} (Debian packages the external checks run)" >&2
            apt-get update -qq
            DEBIAN_FRONTEND=noninteractive apt-get install -y -qq "${missing_packages[@]}" > /dev/null
        else
            problems+=("missing ${missing_packages[*]}: install with  sudo apt-get install -y ${missing_packages[*]}")
        fi
    fi
    $is_root || problems+=("not root: the Slurm check starts a real cluster (Debian's slurmctld, slurmd, munge); run  sudo scripts/test.sh")
    if ! command -v python3 > /dev/null; then
        problems+=("no python3 for peers/.venv: install with  sudo apt-get install -y python3 python3-venv")
    fi
    if [ ${#problems[@]} -gt 0 ]; then
        echo "scripts/test.sh: the external checks cannot run here:" >&2
        for p in "${problems[@]}"; do echo "  - $p" >&2; done
        echo "  or run  scripts/test.sh --skip-external  to run without them (they are counted as not run)" >&2
        exit 2
    fi
    python3 peers/setup_venv.py > /dev/null
fi

ledger=""
if $skip_external; then
    mkdir -p target
    # One ledger per run, so that runs side by side do not share one.
    ledger="$(mktemp -p "$(pwd)/target" skipped-external-checks.XXXXXX)"
    export SOLSIM_SKIP_EXTERNAL="$ledger"
else
    unset SOLSIM_SKIP_EXTERNAL
fi

status=0
cargo test --workspace "${cargo_args[@]}" || status=$?

if $skip_external; then
    n=$(wc -l < "$ledger")
    echo
    if [ "$n" -eq 0 ]; then
        echo "external checks: all ran (--skip-external was given, but nothing was missing)"
    else
        echo "external checks: $n did not run (--skip-external), by what was missing:"
        cut -f2,3 "$ledger" | sort | uniq -c | sort -rn | sed "s/^ *//" |
            awk -F'\t' '{ printf "  %s  (install: %s)\n", $1, $2 }'
        echo "  each check: $ledger"
    fi
fi
exit "$status"
