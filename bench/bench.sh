#!/bin/sh
# make bench: times the assignment image. For each configuration, RUNS runs of the whole
# process, timed from outside, and the render alone, as `ray --stats` reports it; prints the
# medians and Mrays/s (rays cast / render seconds).
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
    process_ms=$(median <"$out/process" | awk '{ printf "%.1f", $1 / 1000 }')
    render_ms=$(median <"$out/render" | awk '{ printf "%.1f", $1 * 1000 }')
    mrays=$(awk -v r="$rays" -v t="$render_ms" 'BEGIN { printf "%.1f", r / (t / 1000) / 1e6 }')
    printf '| %-34s | %8s | %9s | %8s | %7s |\n' "$label" "$process_ms" "$render_ms" "$rays" "$mrays"
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
