#!/usr/bin/env bash
# Side-by-side comparison of surfgrav's exact interaction with GUBAS-RS's mutual-potential series
# (issues 11 and 13). Builds GUBAS-RS outside the surfgrav tree, runs surfgrav's `gubas_compare`
# example for the exact values, then the driver in ./driver for GUBAS's values, errors and times.
#
#   tools/gubas/run.sh [ORDER...]        (default orders: 2 4 8)
#
# Environment:
#   GUBAS_SRC   a GUBAS-RS checkout (default: clone https://github.com/giovannifereoli/GUBAS-RS into
#               $WORK and check out $GUBAS_COMMIT)
#   WORK        scratch folder outside the tree (default /tmp/gubas-compare)
#   SURFGRAV_ROOT     the surfgrav tree whose engine is measured (default: this one; a clean
#                     export such as `git archive HEAD | tar -x -C DIR` keeps others' work in
#                     progress out of the figures)
#   SURFGRAV_COMMIT   the commit that tree is (default: git rev-parse HEAD in it)
#   CARGO_TARGET_DIR  as usual (default: SURFGRAV_ROOT/target)
# Writes results/surfgrav_exact.csv, results/gubas.csv and results/conditions.txt.
set -euo pipefail
GUBAS_COMMIT=2a07388530dbc1691e6048b8cc98f25ff1160df6
here="$(cd "$(dirname "$0")" && pwd)"
root="${SURFGRAV_ROOT:-$(cd "$here/../.." && pwd)}"
target="${CARGO_TARGET_DIR:-$root/target}"
commit="${SURFGRAV_COMMIT:-$(git -C "$root" rev-parse HEAD)}"
WORK="${WORK:-/tmp/gubas-compare}"
orders=("$@")
[ ${#orders[@]} -gt 0 ] || orders=(2 4 8)
mkdir -p "$WORK" "$here/results"

if [ -z "${GUBAS_SRC:-}" ]; then
    GUBAS_SRC="$WORK/GUBAS-RS"
    [ -d "$GUBAS_SRC/.git" ] || git clone -q https://github.com/giovannifereoli/GUBAS-RS "$GUBAS_SRC"
    git -C "$GUBAS_SRC" checkout -q "$GUBAS_COMMIT"
fi

# The driver, built against that GUBAS-RS, with its own target folder (one job: a shared machine).
rm -rf "$WORK/driver"
cp -r "$here/driver" "$WORK/driver"
sed "s#@GUBAS_RS@#$GUBAS_SRC/gubas_rs#" "$here/driver/Cargo.toml.in" > "$WORK/driver/Cargo.toml"
rm "$WORK/driver/Cargo.toml.in"
CARGO_TARGET_DIR="$WORK/target" cargo build --release -j1 --manifest-path "$WORK/driver/Cargo.toml"

# surfgrav's exact values and times (one thread; both programs are single-threaded).
(cd "$root" && CARGO_TARGET_DIR="$target" cargo build --release -j1 -p surfgrav-interaction --example gubas_compare)
{
    echo "date: $(date -u +%Y-%m-%dT%H:%M:%SZ)"
    echo "cpu: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), $(nproc) cores"
    echo "surfgrav: $commit"
    echo "gubas-rs: $(git -C "$GUBAS_SRC" rev-parse HEAD 2>/dev/null || echo "$GUBAS_COMMIT (archive)")"
    echo "load before surfgrav: $(cut -d' ' -f1-3 /proc/loadavg)"
} > "$here/results/conditions.txt"
RAYON_NUM_THREADS=1 "$target/release/examples/gubas_compare" \
    > "$here/results/surfgrav_exact.csv"
echo "load before gubas: $(cut -d' ' -f1-3 /proc/loadavg)" >> "$here/results/conditions.txt"
"$WORK/target/release/gubas-compare-driver" "$here/results/surfgrav_exact.csv" \
    "$GUBAS_SRC/example" "${orders[@]}" > "$here/results/gubas.csv"
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)" >> "$here/results/conditions.txt"
python3 "$here/table.py" "$here/results" > "$here/results/tables.md"
cat "$here/results/tables.md"
