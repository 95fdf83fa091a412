#!/usr/bin/env bash
# Times globular's surfacing against OpenVDB's own vdb_tool (Debian libopenvdb-tools) on
# the same particles at the same voxel size, and prints a table with the ratio.
#
#   bench/surface_vs_vdb_tool.sh [BUILD_DIR] [COUNT...]     (default: build 1e4 1e5 1e6)
#   REPEAT=3 bench/surface_vs_vdb_tool.sh ...   fastest of 3 runs each (shared machines)
#
# Particles: bench_puddle(COUNT) (bench/surface_bench_scene.h), radius 1, written as a
# PLY point cloud that vdb_tool reads. Both sides run at voxel size 0.25 (globular's
# default, radius / 4) with a 3-voxel half band and produce a uniform mesh written as PLY:
#   globular:  Wyvill metaballs -> narrow-band level set (fieldToLevelSet) -> volumeToMesh
#              -> PLY
#   vdb_tool:  -points2ls (spheres of radius 4 voxels = 1 world unit, the radius of a lone
#              globule's surface) -> -ls2mesh -> -write PLY
# Times are wall seconds of those steps, from each side's own timers: globular's
# "total", vdb_tool's -verbose lines (Points->SDF, SDF->mesh, Write geometry). Reading the
# input and starting the process are left out on both sides.
#
# The last columns are what the surface stage does with the same particles beyond what
# vdb_tool does ("frame": globular_surface_compare frame, fastest of REPEAT): the whole
# frame (surfaceGlobules: also the fog, the "vel" grid and the mesh's per-vertex
# velocity) with its VDB and PLY files written, and the VDB file's size.
set -euo pipefail

build=${1:-build}
shift || true
counts=("$@")
((${#counts[@]})) || counts=(10000 100000 1000000)
compare="$build/bench/globular_surface_compare"
voxel=0.25
radius_voxels=4
repeat=${REPEAT:-1}

[[ -x "$compare" ]] || { echo "build $compare first (ninja -C $build globular_surface_compare)" >&2; exit 1; }
command -v vdb_tool >/dev/null || { echo "vdb_tool not found: apt-get install libopenvdb-tools" >&2; exit 1; }

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

faces() { grep -a -m1 '^element face' "$1" | awk '{print $3}'; }

printf '%-10s %14s %14s %8s %12s %12s %10s %8s %10s\n' globules "globular (s)" "vdb_tool (s)" \
    ratio "our tris" "vdb faces" "frame (s)" "/ vdb" "VDB (MB)"
for n in "${counts[@]}"; do
    "$compare" points "$n" "$tmp/points.ply"
    ours="" theirs="" frame="" bytes=""
    for ((r = 0; r < repeat; ++r)); do  # alternate the two, keep each side's fastest
        o=$("$compare" time "$n" "$voxel" "$tmp/ours.ply" | awk '$1 == "total" {print $2}')
        t=$(vdb_tool -verbose -read "$tmp/points.ply" \
                -points2ls voxel=$voxel radius=$radius_voxels width=3 \
                -ls2mesh adapt=0 -write "$tmp/vdb_tool.ply" 2>&1 |
            awk '/Points->SDF|SDF -> mesh|Write geometry/ {
                     # "in 413.8 milliseconds", or "in 3 seconds and ... (3429.4ms)"
                     if (match($0, /\([0-9.]+ms\)/)) ms += substr($0, RSTART + 1, RLENGTH - 4)
                     else for (i = 1; i <= NF; ++i) if ($i == "in") ms += $(i + 1) }
                 END { printf "%.3f", ms / 1000 }')
        f=$("$compare" frame "$n" "$voxel" "$tmp/frame")
        ft=$(awk '$1 == "total" {print $2}' <<<"$f")
        bytes=$(awk '$1 == "vdb_bytes" {print $2}' <<<"$f")
        [[ -z "$ours" ]] || (( $(echo "$o < $ours" | bc) )) && ours=$o
        [[ -z "$theirs" ]] || (( $(echo "$t < $theirs" | bc) )) && theirs=$t
        [[ -z "$frame" ]] || (( $(echo "$ft < $frame" | bc) )) && frame=$ft
    done
    tris=$(( $(faces "$tmp/ours.ply") ))
    printf '%-10s %14s %14s %8.2f %12s %12s %10s %8.2f %10.1f\n' "$n" "$ours" "$theirs" \
        "$(echo "$ours / $theirs" | bc -l)" "$tris" "$(faces "$tmp/vdb_tool.ply")" "$frame" \
        "$(echo "$frame / $theirs" | bc -l)" "$(echo "$bytes / 1000000" | bc -l)"
done
echo "ratio = globular / vdb_tool; frame = the surface stage's whole frame and files;"
echo "machine: $(nproc) cores, $(uname -m)"
