#!/usr/bin/env bash
# Runs solsim's benchmarks and their peers in ONE job on this machine and prints ratio tables
# (only ratios taken side by side are meaningful on these noisy machines; PERFORMANCE.md §5).
#
# Usage: peers/run_peer_benchmarks.sh [SECTION...]     (default: all sections)
# Sections: grid (B3 keep-out growth, B4 A*).
#
# The Rust benches build with -C target-cpu=native into their own target dir
# (target/bench-native), so the shared target/ is not rebuilt with other flags.
set -euo pipefail
cd "$(dirname "$0")/.."

BENCH_TARGET="${BENCH_TARGET:-target/bench-native}"

# --- grid: B3 keep-out growth (EDT + threshold) and B4 A* ------------------------------------
section_grid() {
    local grids="$BENCH_TARGET/bench-grids"
    echo "== grid: cargo bench --bench grid (dumps the instances to $grids) =="
    SOLSIM_GRID_DUMP="$grids" RUSTFLAGS="-C target-cpu=native" CARGO_TARGET_DIR="$BENCH_TARGET" \
        cargo bench --bench grid
    echo "== grid: Python peers on the same instances =="
    python3 peers/bench_grid.py peers --grids "$grids" --out "$grids/peers.json"
    echo "== grid: ratios (ours / peer, < 1 = faster) =="
    python3 peers/bench_grid.py report --peers "$grids/peers.json" \
        --criterion "$BENCH_TARGET/criterion" --out "$grids/ratios.json"
}

sections=("$@")
[ ${#sections[@]} -eq 0 ] && sections=(grid)
for s in "${sections[@]}"; do
    "section_$s"
done
