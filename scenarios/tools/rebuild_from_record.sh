#!/usr/bin/env bash
# Rebuild the historic scenarios from the bundled public record (data/m20/M20_traverse.json) with
# `solsim record import`: the scenario, its zones and its procedural map, then the hand-written
# what-if claims of scenarios/claims/NAME.toml appended below a marker line. The bundled files are
# exactly this script's output (tests/record_scenarios.rs rebuilds them and compares).
#
# Usage: scenarios/tools/rebuild_from_record.sh [SOLSIM]   (default target/release/solsim)
set -euo pipefail
cd "$(dirname "$0")/../.."
SOLSIM=${1:-target/release/solsim}
OUT_ROOT=${REBUILD_OUT:-.}

# name, sols, seed
rebuild() {
    local name=$1 sols=$2 seed=$3 tmp
    tmp=$(mktemp -d)
    "$SOLSIM" record import --sols "$sols" --name "$name" --seed "$seed" --out "$tmp/out" > /dev/null
    mkdir -p "$OUT_ROOT/maps/assets/$name" "$OUT_ROOT/scenarios"
    cp "$tmp/out/map/appearance.tif" "$tmp/out/map/dem.tif" "$tmp/out/map/terrain.tif" \
        "$tmp/out/map/recipe.toml" "$OUT_ROOT/maps/assets/$name/"
    cp "$tmp/out/$name.zones.geojson" "$OUT_ROOT/scenarios/"
    sed "s#= \"map/#= \"../maps/assets/$name/#" "$tmp/out/$name.toml" > "$OUT_ROOT/scenarios/$name.toml"
    if [ -f "scenarios/claims/$name.toml" ]; then
        cat "scenarios/claims/$name.toml" >> "$OUT_ROOT/scenarios/$name.toml"
    fi
    rm -rf "$tmp"
}

rebuild rapid-traverse-379-409 379-409 379
rebuild sol383-386 383-386 385
rebuild sol717-719 717-719 717
