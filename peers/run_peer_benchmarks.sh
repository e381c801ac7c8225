#!/usr/bin/env bash
# Runs solsim's benchmarks and their peers in ONE job on this machine and prints ratio tables
# (only ratios taken side by side are meaningful on these noisy machines; docs/design.md,
# "How benchmarks are taken").
#
# Usage: peers/run_peer_benchmarks.sh [SECTION...]     (default: all sections)
# Sections: grid (B3 keep-out growth, B4 A*), campaign (the whole rapid-traverse compare),
#           census (B1 exact census scores, B2 full localization),
#           planner (B6 activity planner, n = 20–320, and the simulator's sol problems against
#           OR-Tools CP-SAT; anytime quality at equal budgets),
#           study (many seeds through the library, map loaded once, against the CLI per run),
#           sweep (Monte Carlo sweeps: cargo bench --bench sweep against pyarrow and scipy, and the
#           issue 11 targets timed end to end with peak memory),
#           filters (one EKF step against filterpy's ExtendedKalmanFilter; the particle filter's
#           update, resampling against filterpy's systematic_resample and numpy).
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

# --- campaign: solsim compare on the rapid traverse (all five strategies) ---------------------
# No tool does this job, so there is no peer: the target is absolute (issue 2: under 2 s), and the
# CLI itself is timed too, as a user runs it (hyperfine if installed, else 5 runs of `time`).
section_campaign() {
    echo "== campaign: cargo bench --bench campaign =="
    RUSTFLAGS="-C target-cpu=native" CARGO_TARGET_DIR="$BENCH_TARGET" cargo bench --bench campaign
    RUSTFLAGS="-C target-cpu=native" CARGO_TARGET_DIR="$BENCH_TARGET" cargo build --release --quiet
    local bin="$BENCH_TARGET/release/solsim"
    local scen=scenarios/rapid-traverse-379-409.toml
    echo "== campaign: the CLI, end to end ($bin compare $scen --no-files) =="
    if command -v hyperfine > /dev/null; then
        hyperfine --warmup 1 --runs 10 "$bin compare $scen --no-files"
    else
        for _ in 1 2 3 4 5; do /usr/bin/time -f "%e s wall" "$bin" compare "$scen" --no-files > /dev/null; done
    fi
}

# --- census: B1 exact masked census scores (brute force, FFT) and B2 full localization --------
section_census() {
    local dump="$BENCH_TARGET/bench-census"
    echo "== census: cargo bench --bench localize (dumps the B1 instance to $dump) =="
    SOLSIM_CENSUS_DUMP="$dump" RUSTFLAGS="-C target-cpu=native" CARGO_TARGET_DIR="$BENCH_TARGET" \
        cargo bench --bench localize
    echo "== census: Python peers on the same instance (scipy.fft f64, 24 x cv2 TM_CCORR f32) =="
    python3 peers/bench_census.py peers --dump "$dump" --out "$dump/peers.json"
    echo "== census: ratios (ours / peer, < 1 = faster) =="
    python3 peers/bench_census.py report --peers "$dump/peers.json" \
        --criterion "$BENCH_TARGET/criterion"
}

# --- planner: B6 time to proven optimum (n = 20 … 320) and the simulator's own sol problems
# against OR-Tools CP-SAT, then anytime quality at equal budgets (1 ms … 1 s) -------------------
section_planner() {
    local dump="$BENCH_TARGET/planner-instances"
    echo "== planner: uptime (load on this 2-core machine) =="
    uptime
    echo "== planner: cargo bench --bench planner (dumps the instances to $dump) =="
    SOLSIM_PLANNER_DUMP="$dump" RUSTFLAGS="-C target-cpu=native" CARGO_TARGET_DIR="$BENCH_TARGET" \
        cargo bench --bench planner
    echo "== planner: CP-SAT (1 and 2 workers) on the same JSON instances: n <= 80 and the sol problems 3 solves each =="
    python3 peers/planner_cpsat.py solve "$dump"/n{20,40,80}_seed?.json "$dump"/sol_*.json \
        --workers 1 2 --repeat 3 --time-limit 120 --out "$dump/cpsat_small.json"
    echo "== planner: CP-SAT on n = 160 and 320, one solve each (up to a minute apiece) =="
    python3 peers/planner_cpsat.py solve "$dump"/n{160,320}_seed?.json \
        --workers 1 2 --repeat 1 --time-limit 120 --out "$dump/cpsat_large.json"
    python3 -c 'import json, sys; json.dump(sum((json.load(open(f)) for f in sys.argv[2:]), []), open(sys.argv[1], "w"), indent=1)' \
        "$dump/cpsat.json" "$dump/cpsat_small.json" "$dump/cpsat_large.json"
    echo "== planner: table (ours / CP-SAT, < 1 = faster) =="
    python3 peers/planner_b6_report.py --peers "$dump/cpsat.json" \
        --criterion "$BENCH_TARGET/criterion" --dump "$dump"
    echo "== planner: anytime, the planner at 1 / 10 / 100 / 1000 ms (n = 80, 160, 320; 3 runs each) =="
    RUSTFLAGS="-C target-cpu=native" CARGO_TARGET_DIR="$BENCH_TARGET" \
        cargo run --release -q -p planner --example anytime -- --out "$dump/anytime_planner.json"
    echo "== planner: anytime, CP-SAT at the same budgets (1 and 2 workers, 3 runs each) =="
    python3 peers/planner_anytime.py solve "$dump"/n{80,160,320}_seed?.json \
        --out "$dump/anytime_cpsat.json"
    python3 peers/planner_anytime.py report --planner "$dump/anytime_planner.json" \
        --cpsat "$dump/anytime_cpsat.json" --known "$dump/cpsat.json" \
        --svg docs/figures/planner_anytime.svg
    uptime
}

# --- study: RUNS run indices × {ground, onboard} of sols 383-386 with the map loaded once
# (study::Scenario, examples/hundred_seeds.rs) against the CLI, which loads per run -----------
section_study() {
    local runs="${STUDY_RUNS:-10}"
    local scen=scenarios/sol383-386.toml
    # Both sides from the one ordinary release build: the ratio is library against CLI.
    cargo build --release --quiet --bin solsim -p solsim
    cargo build --release --quiet -p study --example hundred_seeds
    local bin=target/release/solsim
    local example=target/release/examples/hundred_seeds
    echo "== study: uptime (load on this 2-core machine) =="
    uptime
    for round in 1 2 3; do
        echo "== study: round $round, library, 1 thread ($((2 * runs)) runs, one load) =="
        /usr/bin/time -f "library: %e s wall, %U s user, %M KB peak" \
            env RAYON_NUM_THREADS=1 "$example" "$scen" "$runs"
        echo "== study: round $round, CLI, one process per run ($((2 * runs)) runs) =="
        /usr/bin/time -f "cli: %e s wall, %U s user, %M KB peak" sh -c '
            for _ in $(seq "$1"); do
                for s in ground onboard; do
                    RAYON_NUM_THREADS=1 "$2" run "$3" --strategy "$s" --no-files > /dev/null
                done
            done' sh "$runs" "$bin" "$scen"
    done
    uptime
}

# --- sweep: Monte Carlo sweeps (issue 11) -----------------------------------------------------
# cargo bench --bench sweep (simulation, Parquet table, paired bootstrap) against pyarrow's
# write_table and scipy.stats.bootstrap on the same data; then the targets end to end with
# /usr/bin/time (wall, user, peak RSS): 1000 runs x 5 strategies of the rapid traverse on 1 and
# 2 threads, 200 runs x 5 of sol383-386 (census localizer) on 2 threads; and a sweep against
# what a user had before it, one `solsim compare` process per run.
section_sweep() {
    local dump="$BENCH_TARGET/bench-sweep"
    local runs="${SWEEP_RUNS:-1000}"
    echo "== sweep: uptime (load on this 2-core machine) =="
    uptime
    echo "== sweep: cargo bench --bench sweep (dumps the data to $dump) =="
    SOLSIM_SWEEP_DUMP="$dump" RUSTFLAGS="-C target-cpu=native" CARGO_TARGET_DIR="$BENCH_TARGET" \
        cargo bench --bench sweep
    echo "== sweep: pyarrow and scipy on the same data =="
    python3 peers/bench_sweep.py peers --dump "$dump" --out "$dump/peers.json"
    echo "== sweep: ratios (ours / peer, < 1 = faster) =="
    python3 peers/bench_sweep.py report --peers "$dump/peers.json" --criterion "$BENCH_TARGET/criterion"
    # The end-to-end targets use the ordinary release build, as a user runs it.
    cargo build --release --quiet --bin solsim -p solsim
    local bin=target/release/solsim
    local out
    out=$(mktemp -d)
    for threads in 1 2; do
        echo "== sweep: rapid traverse, $runs runs x 5 strategies, $threads thread(s) (target <= 120 s on 2) =="
        /usr/bin/time -f "rapid traverse $threads thread(s): %e s wall, %U s user, %M KB peak" \
            "$bin" sweep scenarios/rapid-traverse-379-409.toml --runs "$runs" --threads "$threads" \
            --quiet --out "$out/rapid-$threads"
    done
    cmp "$out/rapid-1/runs.parquet" "$out/rapid-2/runs.parquet" && echo "1 and 2 threads: identical runs.parquet"
    # The same with slip from the rapier rover's profile and slip-aware routing (issue 15): a
    # copy of the scenario with absolute map paths and `slip_model = "profile"` under [rover].
    sed -e "s|\"\.\./maps/|\"$PWD/maps/|" -e "s|^zones = \"|zones = \"$PWD/scenarios/|" \
        -e 's|^\[rover\]$|[rover]\nslip_model = "profile"|' \
        scenarios/rapid-traverse-379-409.toml > "$out/rapid-slip-profile.toml"
    echo "== sweep: rapid traverse with slip_model = \"profile\", $runs runs x 5 strategies, 2 threads (target <= 120 s) =="
    /usr/bin/time -f "rapid traverse slip profile 2 threads: %e s wall, %U s user, %M KB peak" \
        "$bin" sweep "$out/rapid-slip-profile.toml" --runs "$runs" --threads 2 --quiet --out "$out/rapid-slip"
    echo "== sweep: sol383-386 (census localizer), 200 runs x 5 strategies, 2 threads (target <= 60 s) =="
    /usr/bin/time -f "sol383-386 census: %e s wall, %U s user, %M KB peak" \
        "$bin" sweep scenarios/sol383-386.toml --runs 200 --threads 2 --quiet --out "$out/s383"
    echo "== sweep: 20 runs as one sweep against 20 solsim compare processes (rapid traverse, 2 threads) =="
    /usr/bin/time -f "sweep --runs 20: %e s wall, %U s user, %M KB peak" \
        "$bin" sweep scenarios/rapid-traverse-379-409.toml --runs 20 --quiet --out "$out/rapid-20"
    /usr/bin/time -f "20 x compare: %e s wall, %U s user, %M KB peak" sh -c '
        for _ in $(seq 20); do "$1" compare "$2" --no-files > /dev/null; done' \
        sh "$bin" scenarios/rapid-traverse-379-409.toml
    rm -rf "$out"
    uptime
}

# --- filters: one EKF step (paper 004) and one particle-filter update (paper 002) -------------
# cargo bench --bench filters (dumps the EKF window and the particle weights and scores), then
# filterpy 2.0.0 and numpy on the same instances, then the table (peer / solsim, > 1 = faster).
section_filters() {
    local dump="$BENCH_TARGET/bench-filters"
    local start=$SECONDS
    echo "== filters: uptime (load on this 2-core machine) =="
    uptime
    echo "== filters: cargo bench --bench filters (dumps the instances to $dump) =="
    SOLSIM_FILTERS_DUMP="$dump" RUSTFLAGS="-C target-cpu=native" CARGO_TARGET_DIR="$BENCH_TARGET" \
        cargo bench --bench filters
    echo "== filters: filterpy and numpy peers on the same instances =="
    python3 peers/bench_filters.py peers --dump "$dump" --out "$dump/peers.json"
    echo "== filters: table (peer / solsim, > 1 = solsim faster) =="
    python3 peers/bench_filters.py report --peers "$dump/peers.json" \
        --criterion "$BENCH_TARGET/criterion"
    uptime
    echo "filters: whole section $((SECONDS - start)) s wall"
}

sections=("$@")
[ ${#sections[@]} -eq 0 ] && sections=(grid campaign census planner study sweep filters)
for s in "${sections[@]}"; do
    "section_$s"
done
