#!/usr/bin/env bash
# hcm beside MuJoCo and PyBullet on the real cube tosses (benches/peers/README.md).
#
#   bash benches/peers/run.sh [OUT] [--quick] [--randomised-only]
#   bash benches/peers/run.sh [OUT] --elbow [--quick]
#   bash benches/peers/run.sh [OUT] [--quick] --shards N
#
# OUT (default peers-out/) receives hcm's scores and fit, peers.md, peers.json and
# run.log, then the randomised peers (randomised.py: hcm's ensemble and the peers'
# ensembles on the held-out tosses) in randomised.md and randomised.json, also appended
# to peers.md and peers.json. --quick: the first 40 runs (19 training, 21 held out), a
# short hcm fit, short peer fits and small ensembles (4 members, 3 σ values): a smoke run
# of about a minute (the full run: about 17 min on 2 cores, and the randomised stage).
# --randomised-only: skips hcm's fit and the peers' fits and randomises the fits of
# benches/peers/full-run/peers.json (or of OUT/peers.json if there is one).
# HCM=/path/to/hcm uses that binary; unset, hcm is built with
# `cargo build --release -p hcm-host --bin hcm` and target/release/hcm is used.
# PYTHON picks the interpreter for the venv (default python3.11, else python3).
# --elbow: the real two-link elbow tosses instead (README, "The elbow"): hcm predicts every
# toss with the shipped scenario and with its fitted physics (docs/results/elbow-toss/
# physics.toml), then elbow.py fits MuJoCo and PyBullet on every 4th even toss and scores
# them on the odd ones (--quick: the first 40 runs and short fits, about 20 s).
# --shards N: the peers' fits as N separate processes, each the task of a Slurm job array
# would be (SLURM_ARRAY_TASK_ID of SLURM_ARRAY_TASK_COUNT: peers.py --shard's default),
# then `peers.py --merge`: the same peers.md and peers.json but for the fit times
# (`same_fits.py` compares two OUTs so).
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(cd "$here/../.." && pwd)"
out=peers-out
quick=0
randomised_only=0
elbow=0
shards=0
expect_shards=0
for arg in "$@"; do
    if [ "$expect_shards" = 1 ]; then
        shards="$arg"
        expect_shards=0
        continue
    fi
    case "$arg" in
        --quick) quick=1 ;;
        --shards) expect_shards=1 ;;
        --randomised-only) randomised_only=1 ;;
        --elbow) elbow=1 ;;
        -h|--help) sed -n '2,26p' "$0"; exit 0 ;;
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

# Times one step into run.log.
step() {
    local name="$1"; shift
    local t0=$SECONDS
    "$@" 2>&1 | tee -a "$log"
    say "[$name: $((SECONDS - t0)) s]"
}

if [ "$elbow" = 1 ]; then
    [ "$randomised_only" = 0 ] || { echo "--elbow has no randomised stage" >&2; exit 2; }
    scenario=scenarios/elbow_toss.toml
    data=data/contactnets-elbow/tosses.csv
    physics=docs/results/elbow-toss/physics.toml
    if [ "$quick" = 1 ]; then
        first=(--first 40)
        peer_fit=(--survey 8 --evaluations 15 --check-tosses 20)
    else
        first=()
        peer_fit=(--survey 32 --evaluations 120)
    fi
    step "hcm predict, shipped scenario" "$HCM" predict --scenario "$scenario" --data "$data" \
        "${first[@]}" --out "$out/predicted_scenario.csv" --scores "$out/scores_scenario.csv"
    step "hcm predict, fitted physics" "$HCM" predict --scenario "$scenario" \
        --physics "$physics" --data "$data" "${first[@]}" --out "$out/predicted_fitted.csv" \
        --scores "$out/scores_fitted.csv"
    step "elbow.py" "$venv/bin/python" "$here/elbow.py" --data "$data" \
        --scenario-scores "$out/scores_scenario.csv" \
        --scenario-predicted "$out/predicted_scenario.csv" \
        --fitted-scores "$out/scores_fitted.csv" --hcm-physics "$physics" --fit-stride 4 \
        --out "$out" "${first[@]}" "${peer_fit[@]}"
    total=$((SECONDS - started))
    say "[total: $total s]"
    {
        echo
        echo "Command: \`bash benches/peers/run.sh OUT --elbow$( [ "$quick" = 1 ] && echo ' --quick')\`;" \
             "wall time $total s on $(nproc) cores (steps: $(grep -o '^\[[^]]*\]' "$log" | tr '\n' ' '))."
    } >> "$out/peers.md"
    exit 0
fi

scenario=scenarios/cube_toss.toml
data=data/contactnets-cube/tosses.csv
if [ "$quick" = 1 ]; then
    first=(--first 40)
    hcm_fit=(--population 8 --generations 2 --polish 6)
    peer_fit=(--survey 8 --evaluations 15 --check-tosses 20)
    members=4
    randomise=(--members 4 --train-members 4 --scatter-grid 0,0.15,0.3 --tilt-grid 0,0.012,0.024)
else
    first=()
    hcm_fit=()
    peer_fit=(--survey 32 --evaluations 120)
    members=32
    randomise=(--members 32 --train-members 8)
fi

step "hcm predict, shipped scenario" "$HCM" predict --scenario "$scenario" --data "$data" \
    "${first[@]}" --out "$out/hcm_scenario_predicted.csv" --scores "$out/hcm_scenario_scores.csv"
if [ "$randomised_only" = 0 ]; then
    step "hcm identify-motion" "$HCM" identify-motion --scenario "$scenario" --data "$data" \
        "${first[@]}" "${hcm_fit[@]}" --out "$out/hcm_fit.toml"
    # The physics file carries the law and friction, and in its `sets` the table offset
    # and inertia identify-motion fitted, which `hcm predict --physics` applies.
    step "hcm predict, fitted" "$HCM" predict --scenario "$scenario" --physics "$out/hcm_fit.toml" \
        --data "$data" "${first[@]}" --out "$out/hcm_fitted_predicted.csv" \
        --scores "$out/hcm_fitted_scores.csv"
    peers=("$venv/bin/python" "$here/peers.py" --data "$data"
        --scenario-scores "$out/hcm_scenario_scores.csv"
        --scenario-predicted "$out/hcm_scenario_predicted.csv"
        --fitted-scores "$out/hcm_fitted_scores.csv" --hcm-fit "$out/hcm_fit.toml"
        --out "$out" "${first[@]}" "${peer_fit[@]}")
    if [ "$shards" -gt 0 ]; then
        files=()
        for ((i = 0; i < shards; i++)); do
            SLURM_ARRAY_TASK_ID=$i SLURM_ARRAY_TASK_COUNT=$shards \
                step "peers.py, shard $i/$shards" "${peers[@]}"
            files+=("$out/peers.shard-$i.json")
        done
        step "peers.py --merge" "${peers[@]}" --merge "${files[@]}"
    else
        step "peers.py" "${peers[@]}"
    fi
    fits="$out/peers.json"
    merge=(--merge)
else
    fits="$out/peers.json"
    [ -f "$fits" ] || fits="$here/full-run/peers.json"
    merge=()
fi

# The randomised peers (README, "Randomised peers"): hcm's extended model (the fitted
# physics and the chance its diagnosis named, docs/results/cube-toss/) forecasts the
# held-out tosses by an ensemble, once as it is (start-state draws and tracker noise
# included) and once with the table's tilt alone, as the peers' members draw it; then
# randomised.py fits each peer's σ on the training tosses and scores its ensembles.
extended=docs/results/cube-toss/extended.toml
# The same physics without the variation (a physics file's `sets` win over --set), and
# the named tilt's σ.
fitted=docs/results/cube-toss/physics.toml
tilt="$(grep -o 'variation\.fixed_tilt=[^"]*' "$extended")"
step "split" "$venv/bin/python" "$here/randomised.py" split --data "$data" "${first[@]}" --out "$out"
step "hcm predict, extended model, $members members" "$HCM" predict --scenario "$scenario" \
    --physics "$extended" --data "$out/held_out.csv" --members "$members" --seed 1 \
    --out "$out/hcm_ensemble_members.csv" --scores "$out/hcm_ensemble_scores.csv" \
    --faces "$out/hcm_ensemble_faces.csv"
step "hcm predict, extended model, tilt alone" "$HCM" predict --scenario "$scenario" \
    --physics "$fitted" --set "$tilt" \
    --data "$out/held_out.csv" --members "$members" --seed 1 \
    --out "$out/hcm_tilt_members.csv" --scores "$out/hcm_tilt_scores.csv" \
    --faces "$out/hcm_tilt_faces.csv"
step "randomised.py" "$venv/bin/python" "$here/randomised.py" run --data "$data" \
    --scenario-scores "$out/hcm_scenario_scores.csv" --peers "$fits" \
    --hcm "extended model (tilt σ, start-state draws, tracker noise)" \
        "$out/hcm_ensemble_scores.csv" "$out/hcm_ensemble_faces.csv" \
    --hcm "extended model, tilt σ alone (start fixed, no tracker noise)" \
        "$out/hcm_tilt_scores.csv" "$out/hcm_tilt_faces.csv" \
    --hcm-members "$out/hcm_ensemble_members.csv" \
    --out "$out" "${first[@]}" "${randomise[@]}" "${merge[@]}"

total=$((SECONDS - started))
say "[total: $total s]"
report="$out/peers.md"
[ "$randomised_only" = 1 ] && report="$out/randomised.md"
{
    echo
    echo "Command: \`bash benches/peers/run.sh OUT$( [ "$quick" = 1 ] && echo ' --quick')$( [ "$randomised_only" = 1 ] && echo ' --randomised-only')$( [ "$shards" -gt 0 ] && echo " --shards $shards")\`;" \
         "wall time $total s on $(nproc) cores (steps: $(grep -o '^\[[^]]*\]' "$log" | tr '\n' ' '))."
} >> "$report"
