#!/usr/bin/env bash
# `globular farm` on a one-node Slurm cluster on localhost (scripts/local_slurm.sh):
#  1. a small shot split into chunks on the farm renders byte-identical PNGs (frames and
#     contact sheet) to one local `globular run`;
#  2. a second shot with one render array task cancelled while the shot runs ends with
#     that chunk missing, and `globular farm --resubmit` completes it, identical again.
# Skipped (exit 77) where Slurm is not installed, unless WITH_SLURM=1 (CI), where that
# is a failure. The cluster is always stopped. Usage: farm_slurm_test.sh GLOBULAR
set -euo pipefail
globular=$(realpath "$1")
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
for program in slurmctld slurmd munged sbatch squeue scancel; do
    if ! command -v "$program" >/dev/null; then
        if [[ ${WITH_SLURM:-0} == 1 ]]; then
            echo "FAIL: $program is not installed, and WITH_SLURM=1 asks for this test" >&2
            exit 1
        fi
        echo "SKIPPED: Slurm is not installed ($program missing); WITH_SLURM=1 scripts/setup.sh installs it"
        exit 77
    fi
done

work=$(mktemp -d /tmp/globular-farm-test.XXXXXX)
export GLOBULAR_SLURM_PORT=$((20000 + $$ % 20000))
cleanup() {
    "$root/scripts/local_slurm.sh" stop "$work/slurm" || true
    rm -rf "$work"
}
trap cleanup EXIT
"$root/scripts/local_slurm.sh" start "$work/slurm"
export SLURM_CONF=$work/slurm/slurm.conf

cat >"$work/shot.toml" <<'TOML'
[simulation]
frames = 12
[[emitter]]
type = "helix"
count = 60
radius = 1.0
center = [0.0, 3.0, 0.0]
[surface]
voxel_size = 0.25
[render]
width = 64
height = 48
samples = 1
shadow_map_size = 256
color_by = "speed"
contact_sheet = 4
contact_tile_width = 32
TOML

# The end of every job log of shot $1: why a chunk failed.
show_logs() {
    local log
    for log in "$1"/farm/logs/*; do
        [[ -f $log ]] || continue
        echo "--- $log" >&2
        tail -n 20 "$log" >&2
    done
}

# Waits until no job of shot $1 is in the queue (this cluster runs only this test's jobs).
drain() {
    for _ in $(seq 300); do
        [[ -z $(squeue --noheader) ]] && return 0
        sleep 0.5
    done
    echo "FAIL: the queue did not drain in 150 s:" >&2
    squeue >&2
    show_logs "$1"
    exit 1
}

# Compares every frame and the contact sheet of $1 with the local run.
same_as_local() {
    local n=0
    for png in "$work"/local/frames/frame.*.png "$work/local/contact_sheet.png"; do
        if ! cmp "$png" "$1/${png#"$work"/local/}"; then
            echo "FAIL: $1 differs from the local run" >&2
            show_logs "$1"
            exit 1
        fi
        n=$((n + 1))
    done
    echo "identical to the local run: $n PNGs ($1)"
}

"$globular" run "$work/shot.toml" --out "$work/local" --quiet
"$globular" farm "$work/shot.toml" --out "$work/dry" --chunk 5 --max-running 2 --dry-run >"$work/dry.txt"
grep -q -- '--array=0-2%2' "$work/dry.txt"
grep -q -- '--dependency=aftercorr:<surface>,afterok:<plan>' "$work/dry.txt"
[[ ! -e $work/dry ]] || { echo "FAIL: --dry-run wrote $work/dry" >&2; exit 1; }

# 1. The whole shot on the farm.
"$globular" farm "$work/shot.toml" --out "$work/farm" --chunk 5 --max-running 2
drain "$work/farm"
"$globular" farm --status "$work/farm"
same_as_local "$work/farm"

# 2. Render task 1 cancelled while the shot runs, then resubmitted.
"$globular" farm "$work/shot.toml" --out "$work/farm2" --chunk 5 --max-running 2 | tee "$work/submitted.txt"
render=$(sed -n 's/^submitted render: job \([0-9]*\).*/\1/p' "$work/submitted.txt")
scancel "${render}_1"
drain "$work/farm2"
"$globular" farm --status "$work/farm2" | tee "$work/status.txt"
grep -q 'render .*missing: 1$' "$work/status.txt"
[[ ! -e $work/farm2/frames/frame.0006.png ]]
"$globular" farm --resubmit "$work/farm2" | tee "$work/resubmitted.txt"
grep -q 'submitted render: job [0-9]* (array 1%2)' "$work/resubmitted.txt"
# (`! grep` would not stop the script: set -e ignores a negated command.)
if grep -q 'submitted surface\|submitted sim' "$work/resubmitted.txt"; then
    echo "FAIL: --resubmit resubmitted finished simulation or surface jobs" >&2
    exit 1
fi
drain "$work/farm2"
same_as_local "$work/farm2"
"$globular" farm --resubmit "$work/farm2" | grep -q 'nothing to resubmit'
echo "PASS"
