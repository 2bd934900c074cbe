#!/bin/sh
# make bench: times the assignment image, then what each effect costs. For each configuration,
# RUNS runs of the whole process, timed from outside, and the render alone, as `ray --stats`
# reports it; prints the medians and Mrays/s (rays cast / render seconds).
set -eu
RUNS=${RUNS:-11}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

median() { sort -g | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }

# bench LABEL PROGRAM ARGS...: one row of the table
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
    if [ "${TABLE:-speed}" = effects ]; then
        set -- $kinds
        printf '| %-40s | %9s | %8s | %8s | %8s | %8s | %-40s |\n' "$label" "$render_ms" "$1" "$2" "$3" "$4" "$effects"
    else
        printf '| %-34s | %8s | %9s | %8s | %7s |\n' "$label" "$process_ms" "$render_ms" "$rays" "$mrays"
    fi
}

echo "Assignment image, 512 x 512, medians of $RUNS runs on $(nproc) cores ($(date -u +%Y-%m-%d))"
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

# What each effect costs: the same scene with one effect's keyword taken out. The scene files are
# rewritten by sed into a temporary directory; nothing else changes.
cp scenes/test.scene scenes/effects.scene "$out/"
sed 's/ mirror [0-9.]*//' scenes/test.scene >"$out/test_no_mirrors.scene"
sed '/^light /d' scenes/test.scene >"$out/test_no_lights.scene"
sed 's/glass 1.5/diffuse 0.9 0.9 0.9/; s/glass 1.33/diffuse 0.6 0.8 0.9/' scenes/effects.scene >"$out/effects_no_glass.scene"
sed 's/ specular [0-9.]* [0-9.]*//' scenes/effects.scene >"$out/effects_no_specular.scene"
sed 's/ mirror [0-9.]*//' scenes/effects.scene >"$out/effects_no_mirrors.scene"
echo
echo "What each effect costs: render time (median of $RUNS, $(nproc) threads) and rays by kind"
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
