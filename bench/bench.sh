#!/bin/sh
# make bench: the speed of the assignment image, what each effect costs, and what accuracy costs
# in time. Whole-process times are measured from outside (RUNS runs, median); render times are
# what `ray --stats` reports; the accuracy tables come from build/*/rtbench (bench/bench.cpp).
set -eu
RUNS=${RUNS:-11}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
echo "make bench on $(nproc) cores, $(date -u +%Y-%m-%d)" >&2

median() { sort -g | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }

# time_process COMMAND...: the median wall time of RUNS runs, in ms
time_process() {
    : >"$out/process"
    for k in $(seq "$RUNS"); do
        start=$(date +%s%N)
        "$@" >/dev/null 2>&1
        end=$(date +%s%N)
        echo "$(( (end - start) / 1000 ))" >>"$out/process"
    done
    median <"$out/process" | awk '{ printf "%.1f", $1 / 1000 }'
}

# bench LABEL PROGRAM ARGS...: one row of a table
bench() {
    label=$1
    shift
    : >"$out/process"
    : >"$out/render"
    for k in $(seq "$RUNS"); do
        start=$(date +%s%N)
        "$@" -o "$out/image.png" --stats 2>"$out/stats"
        end=$(date +%s%N)
        echo "$(( (end - start) / 1000 ))" >>"$out/process"
        sed -n 's/^time: render \([0-9.]*\) s.*/\1/p' "$out/stats" >>"$out/render"
    done
    rays=$(sed -n 's/^rays: .*total=\([0-9]*\)$/\1/p' "$out/stats")
    kinds=$(sed -n 's/^rays: primary=\([0-9]*\) shadow=\([0-9]*\) reflection=\([0-9]*\) refraction=\([0-9]*\).*/\1 \2 \3 \4/p' "$out/stats")
    effects=$(sed -n 's/^effects: //p' "$out/stats")
    process_ms=$(median <"$out/process" | awk '{ printf "%.1f", $1 / 1000 }')
    render_ms=$(median <"$out/render" | awk '{ printf "%.1f", $1 * 1000 }')
    mrays=$(awk -v r="$rays" -v t="$render_ms" 'BEGIN { printf "%.1f", r / (t / 1000) / 1e6 }')
    echo "bench: $label" >&2
    if [ "${TABLE:-speed}" = effects ]; then
        set -- $kinds
        printf '| %-40s | %9s | %8s | %8s | %8s | %8s | %-40s |\n' "$label" "$render_ms" "$1" "$2" "$3" "$4" "$effects"
    else
        printf '| %-34s | %8s | %9s | %8s | %7s |\n' "$label" "$process_ms" "$render_ms" "$rays" "$mrays"
    fi
}

echo "## Speed: the assignment image, 512 x 512 (medians of $RUNS runs, $(nproc) cores)"
echo
printf '| %-34s | %8s | %9s | %8s | %7s |\n' "run" "process" "render" "rays" "Mrays/s"
printf '| %-34s | %8s | %9s | %8s | %7s |\n' "" "ms" "ms" "" ""
echo "|------------------------------------|----------|-----------|----------|---------|"
bench "./ray (all threads)" ./ray
bench "./ray --threads 1" ./ray --threads 1
bench "./ray_float (all threads)" ./ray_float
bench "./ray --triangle cramer" ./ray --triangle cramer
bench "./ray --spp 16 (all threads)" ./ray --spp 16
bench "./ray --spp 16 --threads 1" ./ray --spp 16 --threads 1
bench "./ray_float --spp 16 --threads 1" ./ray_float --spp 16 --threads 1

# The floor: a process that only writes the same PNG with the same settings
./ray -o "$out/reference.png"
build/double/rtbench raw "$out/reference.png" "$out/reference.rgb"
floor=$(time_process build/double/rtbench pngfloor "$out/reference.rgb" "$out/floor.png")
whole=$(time_process ./ray -o "$out/whole.png")
echo
echo "Whole process: ./ray $whole ms; a process that only writes the same PNG: $floor ms;" \
     "ratio $(awk -v a="$whole" -v b="$floor" 'BEGIN { printf "%.2f", a / b }')"

# What each effect costs: the same scene with one effect's keyword taken out. The scene files are
# rewritten by sed into a temporary directory; nothing else changes.
cp scenes/test.scene scenes/effects.scene "$out/"
sed 's/ mirror [0-9][0-9.]*//' scenes/test.scene >"$out/test_no_mirrors.scene"
sed '/^light /d' scenes/test.scene >"$out/test_no_lights.scene"
sed 's/glass 1.5/diffuse 0.9 0.9 0.9/; s/glass 1.33/diffuse 0.6 0.8 0.9/' scenes/effects.scene >"$out/effects_no_glass.scene"
sed 's/ specular [0-9][0-9.]* [0-9][0-9.]*//' scenes/effects.scene >"$out/effects_no_specular.scene"
sed 's/ mirror [0-9][0-9.]*//' scenes/effects.scene >"$out/effects_no_mirrors.scene"
RUNS=5
echo
echo "## What each effect costs: render time (median of $RUNS, $(nproc) threads) and rays by kind"
echo
TABLE=effects
printf '| %-40s | %9s | %8s | %8s | %8s | %8s | %-40s |\n' "scene" "render ms" "primary" "shadow" "reflect" "refract" "effects"
echo "|------------------------------------------|-----------|----------|----------|----------|----------|------------------------------------------|"
bench "test scene" ./ray "$out/test.scene"
bench "test scene, mirror keywords removed" ./ray "$out/test_no_mirrors.scene"
bench "test scene, lights removed" ./ray "$out/test_no_lights.scene"
bench "test scene, --spp 4" ./ray "$out/test.scene" --spp 4
bench "effects gallery" ./ray "$out/effects.scene"
bench "effects gallery, glass made matte" ./ray "$out/effects_no_glass.scene"
bench "effects gallery, specular removed" ./ray "$out/effects_no_specular.scene"
bench "effects gallery, mirror keywords removed" ./ray "$out/effects_no_mirrors.scene"

# What accuracy costs in time: bench/results.csv, results.md, accuracy_vs_time.svg, heat maps
echo "scene,knob,setting,spp,seconds,rays,rmse,psnr,off1,off8" >"$out/results.csv"
build/double/rtbench rows bench >>"$out/results.csv"
build/float/rtbench rows bench >>"$out/results.csv"
cp "$out/results.csv" bench/results.csv
build/double/rtbench report bench
echo
cat bench/results.md
