#!/bin/sh
# bench/kernels.sh OUT REPORT RUNS: rt's triangle search beside the fastest CPU kernels (bench.sh
# runs it from peers.sh; OUT is its scratch folder), written to build/bench/kernels.md and
# appended to REPORT: eye rays at icospheres of
# 1,280, 81,920 and 1,310,720 triangles (rays a second, build time, bytes a triangle), and the
# cracks of each (bench/peers.h says how each is aimed). Each library that is not on the machine
# is skipped with a line that says how to get it:
#   Embree 3: Debian's libembree-dev (apt-get install libembree-dev)
#   tinybvh:  git clone https://github.com/jbikker/tinybvh; TINYBVH=path/to/tinybvh make bench
#   bvh v2:   git clone https://github.com/madmann91/bvh; BVH2=path/to/bvh make bench
# Their sources are copied into build/peers/ and built there; nothing of them is part of rt.
set -eu
out=$1 whole=$2 runs=$3
report=build/bench/kernels.md # (its own file too, appended to the whole report at the end)
: >"$report"
. bench/stats.sh
peers=build/peers
mkdir -p "$peers"

# ---- which programs: rt in double and float, and each library found -----------------------
names="rt rt_float" labels="rt|rt float"
programs="build/peer_rt build/peer_rt_float"
skipped=""
add() { names="$names $1" labels="$labels|$2" programs="$programs $3"; }
if [ -f /usr/include/embree3/rtcore.h ] && make -s build/peer_embree 2>/dev/null; then
    add embree "Embree 3" build/peer_embree
else
    skipped="$skipped\n- Embree: skipped (apt-get install libembree-dev)"
fi
tinybvh=${TINYBVH:-}
if [ -n "$tinybvh" ] && [ -f "$tinybvh/tiny_bvh.h" ]; then
    # (its watertight test's occlusion query reads u and v, which that test leaves undeclared:
    # they are declared in the copy, as its intersection query declares them)
    mkdir -p "$peers/tinybvh_src"
    sed 's/^\tif (t < 0 || t > ray.hit.t) return false;$/&\n\tconst float u = U * invDet, v = V * invDet;/' \
        "$tinybvh/tiny_bvh.h" >"$peers/tinybvh_src/tiny_bvh.h"
    c="g++ -O3 -mavx2 -mfma -std=c++17 -w -I$peers/tinybvh_src -pthread"
    $c -o "$peers/tinybvh" bench/peer_tinybvh.cpp
    $c -ffp-contract=off -DWATERTIGHT_TRITEST -o "$peers/tinybvh_watertight" bench/peer_tinybvh.cpp
    add tinybvh "tinybvh BVH8_CPU" "$peers/tinybvh"
else
    skipped="$skipped\n- tinybvh: skipped (git clone https://github.com/jbikker/tinybvh; TINYBVH=path/to/tinybvh make bench)"
fi
bvh2=${BVH2:-}
if [ -n "$bvh2" ] && [ -f "$bvh2/src/bvh/v2/bvh.h" ]; then
    g++ -O3 -march=native -std=c++20 -w -I"$bvh2/src" -o "$peers/bvh2" bench/peer_bvh2.cpp -pthread
    add bvh2 "bvh v2" "$peers/bvh2"
else
    skipped="$skipped\n- bvh v2: skipped (git clone https://github.com/madmann91/bvh; BVH2=path/to/bvh make bench)"
fi
label() { echo "$labels" | cut -d'|' -f"$1"; }
# header SUFFIX [ratios]: a table's header and alignment rows, a column a program (its label and
# SUFFIX), and with `ratios` one more for each library: rt's share of it
header() {
    line='| triangles |' rule='|---:|'
    i=1
    for n in $names; do line="$line $(label $i)$1 |" rule="$rule---:|" i=$((i + 1)); done
    if [ "${2:-}" = ratios ]; then
        i=1
        for n in $names; do
            case $n in rt*) ;; *) line="$line rt of $(label $i) |" rule="$rule---:|" ;; esac
            i=$((i + 1))
        done
    fi
    echo "$line" && echo "$rule"
}

# ---- rays, build and bytes: RUNS runs in turn, each program's build and 3 rounds a run ------
{
echo
echo "### rt's triangle search beside the fastest CPU kernels: 512 x 512 eye rays at an icosphere, one thread ($runs runs in turn)"
printf "$skipped\n"
echo
echo "Ray ms (median of each run's 3 rounds), then rt's rays a second as a share of each library's (median of the runs' ratios, quartiles):"
echo
header " ms" ratios
} >>"$report"
: >"$out/bytes" && : >"$out/builds"
for level in 3 6 8; do
    triangles=$((20 * (1 << (2 * level))))
    build/make_mesh sphere "$level" >"$out/ico.obj"
    for n in $names; do : >"$out/ms_$n" && : >"$out/build_$n"; done
    for k in $(seq "$runs"); do
        set -- $programs
        for n in $names; do
            "$1" time "$out/ico.obj" 3 >"$out/one"
            head -1 "$out/one" >>"$out/build_$n"
            sed -n '2,4p' "$out/one" >"$out/three" && median "$out/three" >>"$out/ms_$n"
            sed -n 's/^bytes //p' "$out/one" >"$out/bytes_$n"
            shift
        done
    done
    row="| $triangles |"
    for n in $names; do row="$row $(spread "$out/ms_$n") |"; done
    for n in $names; do case $n in rt*) ;; *) row="$row $(ratio "$out/ms_$n" "$out/ms_rt" | sed 's/ (quartiles \(.*\))/ (\1)/; s/, within noise//') |" ;; esac; done
    echo "$row" >>"$report"
    row="| $triangles |"
    for n in $names; do row="$row $(spread "$out/build_$n") |"; done
    for n in $names; do case $n in rt*) ;; *) row="$row $(ratio "$out/build_rt" "$out/build_$n" | sed 's/ (quartiles \(.*\))/ (\1)/; s/, within noise//') |" ;; esac; done
    echo "$row" >>"$out/builds"
    row="| $triangles |"
    for n in $names; do row="$row $(awk -v b="$(cat "$out/bytes_$n")" -v t="$triangles" 'BEGIN { printf "%.1f MB, %.0f B", b / 1e6, b / t }') |"; done
    echo "$row" >>"$out/bytes"
    echo "bench: kernels at $triangles triangles done" >&2
done
{
echo
echo "Build ms (one thread), then rt's build time as a share of each library's:"
echo
header "" ratios
cat "$out/builds"
echo
echo "Each structure's bytes, and bytes a triangle (rt: its committed layout, the scene's own triangles not counted; Embree: all it allocates, by its memory monitor; tinybvh: its traversal data; bvh v2: nodes, order and precomputed triangles):"
echo
header ""
cat "$out/bytes"
} >>"$report"

# ---- cracks: each crack set, at 81,920 and 1,310,720 triangles ------------------------------
crackers="build/peer_rt:rt build/peer_rt_float:rt_float"
[ -x build/peer_embree ] && crackers="$crackers build/peer_embree:embree build/peer_embree@robust:embree_robust"
[ -x "$peers/tinybvh" ] && crackers="$crackers $peers/tinybvh:tinybvh $peers/tinybvh_watertight:tinybvh_watertight"
[ -x "$peers/bvh2" ] && crackers="$crackers $peers/bvh2:bvh2"
{
echo
echo "Cracks: rays that a closed icosphere should stop and that slip through (bench/peers.h: from its centre to every vertex and edge midpoint, and from the eye to those of the cap that faces it), as a share of the rays aimed:"
echo
echo "| triangles | program | vertices, from inside | edges, from inside | vertices, from the eye | edges, from the eye |"
echo "|---:|---|---:|---:|---:|---:|"
} >>"$report"
for level in 6 8; do
    build/make_mesh sphere "$level" >"$out/ico.obj"
    for entry in $crackers; do
        program=${entry%%:*} name=${entry#*:}
        case $program in *@robust) set -- "${program%@robust}" cracks-robust ;; *) set -- "$program" cracks ;; esac
        "$1" "$2" "$out/ico.obj" >"$out/cracks"
        row="| $((20 * (1 << (2 * level)))) | $name |"
        row="$row $(awk -F'\t' '{ printf " %d of %d (%.2f%%) |", $3, $2, 100 * $3 / $2 }' "$out/cracks")"
        echo "$row" >>"$report"
    done
done
echo "bench: cracks done" >&2
cat "$report" >>"$whole"
