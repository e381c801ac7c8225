#!/usr/bin/env bash
# Writes every output the redesign of issue 29 must keep byte-identical into one directory, so two
# builds can be compared with `diff -r`:
#
#   scripts/golden_outputs.sh target/release/solsim /tmp/before
#   (change the code, rebuild)
#   scripts/golden_outputs.sh target/release/solsim /tmp/after
#   diff -r /tmp/before /tmp/after
#
# For every bundled scenario: `compare --json` (standard output) and the `compare --out --report`
# directory; the rapid traverse's 40-run `sweep` Parquet and summary; `plan --json` of the bundled
# campaign file; `regress scenarios/` as text and JSON, with the measured seconds (wall-clock time,
# the only nondeterministic field) replaced by "S".
set -euo pipefail
solsim=$(realpath "${1:?usage: golden_outputs.sh SOLSIM OUT_DIR}")
out=${2:?usage: golden_outputs.sh SOLSIM OUT_DIR}
root=$(cd "$(dirname "$0")/.." && pwd)
rm -rf "$out"
mkdir -p "$out/compare" "$out/sweep" "$out/plan" "$out/regress"
out=$(realpath "$out")
cd "$root"
for s in scenarios/*.toml; do
    n=$(basename "$s" .toml)
    "$solsim" compare "$s" --json --no-files > "$out/compare/$n.json"
    "$solsim" compare "$s" --out "$out/compare/$n" --report > "$out/compare/$n.txt"
done
"$solsim" sweep scenarios/rapid-traverse-379-409.toml --runs 40 --threads 2 \
    --out "$out/sweep/rapid-traverse-379-409" > "$out/sweep/stdout.txt"
for p in scenarios/plans/*.toml; do
    "$solsim" plan "$p" --json > "$out/plan/$(basename "$p" .toml).json"
done
set +e
"$solsim" regress scenarios/ -q > "$out/regress/text.txt"
echo "exit $?" >> "$out/regress/text.txt"
"$solsim" regress scenarios/ -q --json > "$out/regress/json.json"
set -e
sed -i -E 's/[0-9]+(\.[0-9]+)? ?s\b/S/g' "$out/regress/text.txt"
sed -i -E 's/run indices in [0-9.]+ s/run indices in S/' "$out/sweep/stdout.txt"
sed -i -E 's/"seconds": ?[0-9.e+-]+/"seconds":"S"/g' "$out/regress/json.json"
# The output directory's own path, printed by `compare`, differs between the two trees.
find "$out" -name '*.txt' -exec sed -i "s|$out|OUT|g" {} +
echo "golden outputs in $out: $(find "$out" -type f | wc -l) files"
