#!/usr/bin/env bash
# End-to-end benchmark of issue 7: the film-style pour of scenes/bench/pour_1e5.toml
# (100,000 globules, 240 frames at 24 fps) through all three stages, one after the other
# as `globular run` would chain them, each timed on its own:
#
#   bench/end_to_end.sh [BUILD_DIR] [OUT_DIR]      (defaults: build, a temporary directory)
#   FRAMES=24 bench/end_to_end.sh ...              a shorter shot (the first FRAMES frames)
#   LOOK=paper bench/end_to_end.sh ...             the paper's look: an opaque shaded surface,
#                                                  no tone mapping (default LOOK=film: the
#                                                  liquid look with ACES tone mapping)
#   FIXED_DT=1 bench/end_to_end.sh ...             the paper's fixed dt 0.001 instead of
#                                                  adaptive steps
#
# Prints, per stage and in total: wall seconds, peak resident memory (of that stage's
# process; the total's is the largest), and what was written. OUT_DIR is kept when given.
set -euo pipefail

build=${1:-build}
root=$(cd "$(dirname "$0")/.." && pwd)
scene="$root/scenes/bench/pour_1e5.toml"
globular="$build/globular"
[[ -x $globular ]] || { echo "build $globular first (scripts/setup.sh)" >&2; exit 1; }
[[ -x /usr/bin/time ]] || { echo "/usr/bin/time not found: apt-get install time" >&2; exit 1; }

if [[ -n ${2:-} ]]; then
    out=$2
else
    out=$(mktemp -d)
    trap 'rm -rf "$out"' EXIT
fi
frames=${FRAMES:-240}
args=(--out "$out" --quiet --set "simulation.frames=$frames")
look=${LOOK:-film}
case $look in
    film) ;;
    paper) args+=(--set material.look=opaque --set render.tone_mapping=none) ;;
    *) echo "LOOK must be film or paper, not '$look'" >&2; exit 1 ;;
esac
[[ ${FIXED_DT:-0} == 1 ]] && args+=(--set simulation.adaptive=false --set simulation.dt=0.001)

printf '# end to end: %s, %s frames, %s look, %s, %s cores\n' "$(basename "$scene")" "$frames" \
    "$look" "$([[ ${FIXED_DT:-0} == 1 ]] && echo 'fixed dt 0.001' || echo 'adaptive steps')" "$(nproc)"
printf '%-8s %10s %14s  %s\n' stage "wall (s)" "peak RSS (MiB)" written
total_wall=0 peak=0
for stage in sim surface render; do
    stats=$(mktemp)
    /usr/bin/time -f '%e %M' -o "$stats" "$globular" run "$scene" "${args[@]}" --stages "$stage"
    read -r wall kib <"$stats"
    rm -f "$stats"
    case $stage in
        sim) what="$(find "$out/cache" -type f | wc -l) cache files" ;;
        surface) what="$(find "$out/surface" "$out/mesh" -type f 2>/dev/null | wc -l) VDB + mesh files" ;;
        render) what="$(find "$out" -name '*.png' | wc -l) PNG frames" ;;
    esac
    printf '%-8s %10.1f %14.0f  %s, %s\n' "$stage" "$wall" "$((kib / 1024))" "$what" \
        "$(du -sh "$out" | cut -f1) on disk so far"
    total_wall=$(awk -v a="$total_wall" -v b="$wall" 'BEGIN {print a + b}')
    ((kib > peak)) && peak=$kib
done
printf '%-8s %10.1f %14.0f\n' total "$total_wall" "$((peak / 1024))"
tail -1 "$out/stats.csv" | awk -F, '{print "# last frame: " $0}'
