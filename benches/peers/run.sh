#!/usr/bin/env bash
# hcm beside MuJoCo and PyBullet on the real cube tosses (benches/peers/README.md).
#
#   bash benches/peers/run.sh [OUT] [--quick]
#
# OUT (default peers-out/) receives hcm's scores and fit, peers.md, peers.json and
# run.log. --quick: the first 40 runs (19 training, 21 held out), a short hcm fit and
# short peer fits: a smoke run of about 20 s (the full run: about 17 min on 2 cores).
# HCM=/path/to/hcm uses that binary; unset, hcm is built with
# `cargo build --release -p hcm-host --bin hcm` and target/release/hcm is used.
# PYTHON picks the interpreter for the venv (default python3.11, else python3).
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(cd "$here/../.." && pwd)"
out=peers-out
quick=0
for arg in "$@"; do
    case "$arg" in
        --quick) quick=1 ;;
        -h|--help) sed -n '2,11p' "$0"; exit 0 ;;
        -*) echo "unknown option $arg" >&2; exit 2 ;;
        *) out="$arg" ;;
    esac
done
mkdir -p "$out"
out="$(cd "$out" && pwd)"
log="$out/run.log"
: > "$log"
say() { echo "$*" | tee -a "$log"; }
started=$SECONDS

python="${PYTHON:-$(command -v python3.11 || command -v python3)}"
venv="$here/.venv"
[ -x "$venv/bin/python" ] || "$python" -m venv "$venv"
"$venv/bin/pip" install --quiet --disable-pip-version-check -r "$here/requirements.txt"

if [ -z "${HCM:-}" ]; then
    (cd "$root" && cargo build --release -p hcm-host --bin hcm)
    HCM="$root/target/release/hcm"
fi
say "hcm: $HCM ($("$HCM" --version))"

cd "$root"
scenario=scenarios/cube_toss.toml
data=data/contactnets-cube/tosses.csv
if [ "$quick" = 1 ]; then
    first=(--first 40)
    hcm_fit=(--population 8 --generations 2 --polish 6)
    peer_fit=(--survey 8 --evaluations 15 --check-tosses 20)
else
    first=()
    hcm_fit=()
    peer_fit=(--survey 32 --evaluations 120)
fi

# Times one step into run.log.
step() {
    local name="$1"; shift
    local t0=$SECONDS
    "$@" 2>&1 | tee -a "$log"
    say "[$name: $((SECONDS - t0)) s]"
}

step "hcm predict, shipped scenario" "$HCM" predict --scenario "$scenario" --data "$data" \
    "${first[@]}" --out "$out/hcm_scenario_predicted.csv" --scores "$out/hcm_scenario_scores.csv"
step "hcm identify-motion" "$HCM" identify-motion --scenario "$scenario" --data "$data" \
    "${first[@]}" "${hcm_fit[@]}" --out "$out/hcm_fit.toml"
# The physics file carries the law and friction, and in its `sets` the table offset
# and inertia identify-motion fitted, which `hcm predict --physics` applies.
step "hcm predict, fitted" "$HCM" predict --scenario "$scenario" --physics "$out/hcm_fit.toml" \
    --data "$data" "${first[@]}" --out "$out/hcm_fitted_predicted.csv" \
    --scores "$out/hcm_fitted_scores.csv"
step "peers.py" "$venv/bin/python" "$here/peers.py" --data "$data" \
    --scenario-scores "$out/hcm_scenario_scores.csv" \
    --scenario-predicted "$out/hcm_scenario_predicted.csv" \
    --fitted-scores "$out/hcm_fitted_scores.csv" --hcm-fit "$out/hcm_fit.toml" \
    --out "$out" "${first[@]}" "${peer_fit[@]}"

total=$((SECONDS - started))
say "[total: $total s]"
{
    echo
    echo "Command: \`bash benches/peers/run.sh$( [ "$quick" = 1 ] && echo ' OUT --quick' || echo ' OUT')\`;" \
         "wall time $total s on $(nproc) cores (steps: $(grep -o '^\[[^]]*\]' "$log" | tr '\n' ' '))."
} >> "$out/peers.md"
