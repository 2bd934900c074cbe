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

# run_timed COMMAND...: runs COMMAND once and prints its whole-process wall time in ms, measured
# by rtbench from fork to exit (no shell or `date` process inside the clock)
run_timed() { build/double/rtbench time "$@"; }

# bench LABEL PROGRAM ARGS...: one row of a table
bench() {
    label=$1
    shift
    : >"$out/process"
    : >"$out/render"
    for k in $(seq "$RUNS"); do
        run_timed "$@" -o "$out/image.png" --stats 2>"$out/stats" >>"$out/process"
        sed -n 's/^time: render \([0-9.]*\) s.*/\1/p' "$out/stats" >>"$out/render"
    done
    rays=$(sed -n 's/^rays: .*total=\([0-9]*\)$/\1/p' "$out/stats")
    kinds=$(sed -n 's/^rays: primary=\([0-9]*\) shadow=\([0-9]*\) reflection=\([0-9]*\) refraction=\([0-9]*\).*/\1 \2 \3 \4/p' "$out/stats")
    effects=$(sed -n 's/^effects: //p' "$out/stats")
    process_ms=$(median <"$out/process" | awk '{ printf "%.1f", $1 }')
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
all16=$mrays
bench "./ray --spp 16 --threads 1" ./ray --spp 16 --threads 1
one16=$mrays
bench "./ray_float --spp 16 --threads 1" ./ray_float --spp 16 --threads 1
float16=$mrays

# The floor: a process that only writes the same PNG with the same settings. The two are run
# in turn, RUNS times each, so both medians see the same machine load
./ray -o "$out/reference.png"
build/double/rtbench raw "$out/reference.png" "$out/reference.rgb"
: >"$out/floor"
: >"$out/whole"
for k in $(seq "$RUNS"); do
    run_timed build/double/rtbench pngfloor "$out/reference.rgb" "$out/floor.png" >>"$out/floor"
    run_timed ./ray -o "$out/whole.png" >>"$out/whole"
done
floor=$(median <"$out/floor" | awk '{ printf "%.1f", $1 }')
whole=$(median <"$out/whole" | awk '{ printf "%.1f", $1 }')
ratio=$(awk -v a="$whole" -v b="$floor" 'BEGIN { printf "%.2f", a / b }')
echo
echo "Whole process: ./ray $whole ms; a process that only writes the same PNG: $floor ms;" \
     "ratio $ratio"

# The speed targets against this run's figures
met() { awk -v x="$1" -v op="$2" -v y="$3" 'BEGIN { ok = op == "<=" ? x <= y : x >= y; print ok ? "met" : "not met" }'; }
threads=$(awk -v a="$all16" -v b="$one16" 'BEGIN { printf "%.2f", a / b }')
floatratio=$(awk -v a="$float16" -v b="$one16" 'BEGIN { printf "%.2f", a / b }')
echo
echo "## Speed targets, this run"
echo
echo "| target                                             | measured        | status  |"
echo "|----------------------------------------------------|-----------------|---------|"
printf '| %-50s | %-15s | %-7s |\n' "whole ./ray process <= 25 ms" "$whole ms" "$(met "$whole" "<=" 25)"
printf '| %-50s | %-15s | %-7s |\n' "whole process <= 1.5 x the PNG-only floor" "$ratio x" "$(met "$ratio" "<=" 1.5)"
printf '| %-50s | %-15s | %-7s |\n' "one thread, 16 spp >= 20 Mrays/s" "$one16 Mrays/s" "$(met "$one16" ">=" 20)"
printf '| %-50s | %-15s | %-7s |\n' "$(nproc) threads >= 1.8 x one thread (16 spp)" "$threads x" "$(met "$threads" ">=" 1.8)"
printf '| %-50s | %-15s | %-7s |\n' "ray_float >= ray (one thread, 16 spp)" "$floatratio x" "$(met "$floatratio" ">=" 1)"

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

# Where the robustness claims hold (docs/robustness.md publishes a copy of these tables)
mkdir -p build/bench
{
    build/double/rtbench robustness
    build/float/rtbench robustness
} >build/bench/robustness.md
echo
echo "## Robustness: build/bench/robustness.md"
{
    build/double/rtbench methods build/bench
    build/float/rtbench methods build/bench
} >build/bench/methods.md
echo "## What each method costs and buys: build/bench/methods.md"

# What accuracy costs in time: bench/results.csv, results.md, accuracy_vs_time.svg, heat maps
echo "scene,knob,setting,spp,seconds,rays,rmse,psnr,off1,off8" >"$out/results.csv"
build/double/rtbench rows bench >>"$out/results.csv"
build/float/rtbench rows bench >>"$out/results.csv"
cp "$out/results.csv" bench/results.csv
build/double/rtbench report bench
echo
cat bench/results.md
