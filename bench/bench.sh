#!/bin/sh
# make bench: the speed of the assignment image, what meshes cost by size, what each effect
# costs, and what accuracy costs in time. Everything goes to build/bench/ (speed.md and the
# tables and plots it names); nothing tracked is written. `make bench-publish` copies a run into
# docs/bench/, a deliberate step.
#
# Every time is given as median (min-max) of RUNS runs. Two programs compared are run in turn,
# so both see the same machine load, and their ratio is the median of the pairs' ratios.
set -eu
RUNS=${RUNS:-11}
cores=$(getconf _NPROCESSORS_ONLN 2>/dev/null || echo 1) # (POSIX; nproc is GNU's)
dir=build/bench
mkdir -p "$dir"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
report="$dir/speed.md"
echo "make bench on $cores cores, $(date -u +%Y-%m-%d): writing $dir/" >&2

. bench/stats.sh

{
echo "# make bench, $(date -u +%Y-%m-%d), $cores cores"
echo
echo "Times in ms, median (min-max) of $RUNS runs, run in turn with what they are compared with; a ratio is the median (quartiles) of the ratios of the runs taken in turn."
echo
echo "## The assignment image, 512 x 512"
echo
echo "| run | whole process ms | render ms | Mrays/s |"
echo "|---|---:|---:|---:|"
} >"$report"

for k in $(seq "$RUNS"); do
    timed all ./ray -o "$out/a.png" --stats
    timed one ./ray -o "$out/a.png" --stats --threads 1
    timed all16 ./ray -o "$out/a.png" --stats --spp 16
    timed one16 ./ray -o "$out/a.png" --stats --spp 16 --threads 1
    timed float16 ./ray_float -o "$out/a.png" --stats --spp 16 --threads 1
    timed student16 build/student "$out/s.png" 16
done
{
make_row all "./ray ($cores threads)"
make_row one "./ray --threads 1"
make_row all16 "./ray --spp 16 ($cores threads)"
make_row one16 "./ray --spp 16 --threads 1"
make_row float16 "./ray_float --spp 16 --threads 1"
echo "| build/student 16 (a plain float student solution, -O2) | $(spread "$out/student16") | | |"
echo
echo "- rt against the student solution, 16 spp, one thread: $(ratio "$out/one16" "$out/student16")"
echo "- ray_float against ray, 16 spp, one thread: $(ratio "$out/float16" "$out/one16")"
echo "- one thread against $cores, 16 spp (render): $(ratio "$out/one16.render" "$out/all16.render")"
} >>"$report"

# The floor: a process that only writes the same PNG with the same settings, in turn with ./ray
./ray -o "$out/reference.png"
build/double/rtbench raw "$out/reference.png" "$out/reference.rgb"
for k in $(seq "$RUNS"); do
    timed floor build/double/rtbench pngfloor "$out/reference.rgb" "$out/floor.png"
    timed whole ./ray -o "$out/whole.png"
done
echo "- the whole ./ray process against one that only writes the same PNG: $(ratio "$out/whole" "$out/floor") ($(spread "$out/whole") against $(spread "$out/floor") ms)" >>"$report"
echo "bench: assignment done" >&2

# Meshes by size: the list against the BVH (layout.md, layout.svg), then a million triangles read
# from an OBJ file and rendered whole, with peak memory
build/double/rtbench layout "$dir"
build/make_mesh terrain 708 >"$out/terrain.obj"
printf 'camera lookat 0 1.2 2.2  0 0 0  0 1 0  50\nlight 2 4 2\nmaterial ground diffuse 0.6 0.8 0.5\nmesh terrain.obj ground\n' >"$out/terrain.scene"
: >"$out/million"
for k in 1 2 3; do
    build/double/rtbench timemem ./ray "$out/terrain.scene" -o "$out/terrain.png" --threads 2 >>"$out/million"
done
awk '{ print $1 }' "$out/million" >"$out/million.ms"
awk '{ print $2 }' "$out/million" >"$out/million.mb"
{
echo
echo "## Meshes: render time against size (256 x 256, one thread)"
echo
cat "$dir/layout.md"
echo
echo "![render time against triangles](layout.svg)"
echo
echo "- 1,002,528 triangles (make_mesh terrain 708), read from OBJ and rendered at 512 x 512 on 2 threads,"
echo "  whole process: $(spread "$out/million.ms") ms, peak memory $(spread "$out/million.mb") MB"
} >>"$report"
echo "bench: meshes done" >&2

# Path tracing: the Cornell box at 512 x 512, 64 spp on all cores, and path vertices a second a
# thread (camera, scattered, mirror and glass rays: every ray that extends a path); then error
# against time per method, in double and in float
: >"$out/cornell"
for k in 1 2 3; do
    timed cornell ./ray scenes/cornell.scene -o "$out/cornell.png" --spp 64 --stats
done
vertices=$(sed -n 's/^rays: primary=\([0-9]*\) shadow=[0-9]* reflection=\([0-9]*\) refraction=\([0-9]*\) diffuse=\([0-9]*\).*/\1 \2 \3 \4/p' "$out/stats" | awk '{ print $1 + $2 + $3 + $4 }')
build/double/rtbench path "$dir"
build/float/rtbench path "$dir"
{
echo
echo "## Path tracing (shading path)"
echo
echo "- scenes/cornell.scene, 512 x 512, 64 spp, $cores threads: render $(spread "$out/cornell.render") ms;"
echo "  $vertices path vertices: $(awk -v v="$vertices" -v t="$(median "$out/cornell.render")" -v n="$cores" 'BEGIN { printf "%.2f", v / (t / 1000) / n / 1e6 }') million a second a thread"
echo
echo "Error against time, 96 x 96, RMSE in 8-bit levels against 4,096 samples (path.md, path_float.md):"
echo
cat "$dir/path.md"
echo
echo "![Cornell box](path_cornell.svg) ![assignment](path_assignment.svg)"
echo
echo "Float:"
echo
cat "$dir/path_float.md"
} >>"$report"
echo "bench: path tracing done" >&2

# What each effect costs: the same scene with one effect's keyword taken out
cp scenes/test.scene scenes/effects.scene "$out/"
sed 's/ mirror [0-9][0-9.]*//' scenes/test.scene >"$out/test_no_mirrors.scene"
sed '/^light /d' scenes/test.scene >"$out/test_no_lights.scene"
sed 's/glass 1.5/diffuse 0.9 0.9 0.9/; s/glass 1.33/diffuse 0.6 0.8 0.9/' scenes/effects.scene >"$out/effects_no_glass.scene"
sed 's/ specular [0-9][0-9.]* [0-9][0-9.]*//' scenes/effects.scene >"$out/effects_no_specular.scene"
sed 's/ mirror [0-9][0-9.]*//' scenes/effects.scene >"$out/effects_no_mirrors.scene"
{
echo
echo "## What each effect costs ($cores threads)"
echo
echo "| scene | render ms | primary | shadow | reflection | refraction | effects |"
echo "|---|---:|---:|---:|---:|---:|---|"
} >>"$report"
for scene in test test_no_mirrors test_no_lights effects effects_no_glass effects_no_specular effects_no_mirrors; do
    for k in 1 2 3 4 5; do
        timed "e_$scene" ./ray "$out/$scene.scene" -o "$out/e.png" --stats
    done
    kinds=$(sed -n 's/^rays: primary=\([0-9]*\) shadow=\([0-9]*\) reflection=\([0-9]*\) refraction=\([0-9]*\).*/\1 | \2 | \3 | \4/p' "$out/stats")
    effects=$(sed -n 's/^effects: //p' "$out/stats")
    echo "| $scene | $(spread "$out/e_$scene.render") | $kinds | $effects |" >>"$report"
done
echo "bench: effects done" >&2

# The shadow terminator of smooth icospheres of 80 and 320 triangles: the handouts' methods against
# rt's, in double and float (terminator.md)
build/make_mesh sphere 1 normals >"$dir/ico80.obj"
build/make_mesh sphere 2 normals >"$dir/ico320.obj"
: >"$dir/terminator.md"
build/double/rtbench terminator "$dir" ico80.obj ico320.obj
build/float/rtbench terminator "$dir" ico80.obj ico320.obj
{
echo
echo "## Smooth meshes: the shadow terminator"
cat "$dir/terminator.md"
} >>"$report"
echo "bench: terminator done" >&2

# Where the robustness claims hold, and what each numerical method costs and buys
{
    build/double/rtbench robustness
    build/float/rtbench robustness
} >"$dir/robustness.md"
{
    build/double/rtbench methods "$dir"
    build/float/rtbench methods "$dir"
} >"$dir/methods.md"
echo "bench: robustness and methods done" >&2

# What accuracy costs in time: results.csv, results.md, accuracy_vs_time.svg, heat maps
echo "scene,knob,setting,spp,seconds,rays,rmse,psnr,off1,off8,seconds_min,seconds_max" >"$dir/results.csv"
build/double/rtbench rows "$dir" >>"$dir/results.csv"
build/float/rtbench rows "$dir" >>"$dir/results.csv"
build/double/rtbench report "$dir"
# Peers: smallpt's scene at equal noise, Embree's rays, spheres by the thousand, copies of one
# triangle (bench/peers.sh; each peer skipped, saying how to get it, where it is absent)
sh bench/peers.sh "$out" "$report" "${PEER_RUNS:-5}"
# Ray Tracing in One Weekend's own program on its final scene, at equal error (bench/weekend.sh;
# skipped, saying how to get the book's code, where RTIOW is not set)
sh bench/weekend.sh "${WEEKEND_RUNS:-3}"
cat "$dir/weekend.md" >>"$report"

{
echo
echo "## More: robustness.md, methods.md, results.md (accuracy against time), in this folder"
} >>"$report"
cat "$report"
