#!/bin/sh
# bench/peers.sh OUT REPORT RUNS: rt beside the programs a user might pick instead, appended to
# REPORT (bench.sh runs it; OUT is its scratch folder). Each peer that is not on the machine is
# skipped with a line that says how to get it:
#   smallpt (Kevin Beason, MIT): SMALLPT=path/to/smallpt.cpp make bench
#     (https://www.kevinbeason.com/smallpt/, one thread: its OpenMP line is ignored without -fopenmp)
# and rt's triangle search beside the fastest CPU kernels, Embree 3, tinybvh and bvh v2 (each
# skipped where absent: bench/kernels.sh), and two scaling rows that need no peer: spheres by the
# thousand, and copies of one triangle.
set -eu
out=$1 report=$2 runs=$3
. bench/stats.sh

{
echo
echo "## Peers"
} >>"$report"

# ---- smallpt's Cornell box, at equal error --------------------------------------------------
# Its nine spheres as an rt scene (walls of radius 1e5, a lamp of radius 600 whose cap pokes
# 0.27 below the ceiling); rt's eye rays start on the screen, as smallpt's start 140 along theirs.
cat >"$out/smallpt.scene" <<'EOF'
size 128 96
camera screen 50 52 295.6  5.49666666666667 13.1182244149520 167.138857884618  89.0066666666667 0 0  0 66.6944761293179 -2.84198501682249
shading path
background 0 0 0
depth 1000
material left  diffuse .75 .25 .25
material right diffuse .25 .25 .75
material grey  diffuse .75 .75 .75
material black diffuse 0 0 0
material mirr  mirror 1
material glas  glass 1.5
material lite  diffuse 0 0 0 emit 12 12 12
sphere 100001 40.8 81.6 1e5 left
sphere -99901 40.8 81.6 1e5 right
sphere 50 40.8 100000 1e5 grey
sphere 50 40.8 -99830 1e5 black
sphere 50 100000 81.6 1e5 grey
sphere 50 -99918.4 81.6 1e5 grey
sphere 27 16.5 47 16.5 mirr
sphere 73 16.5 78 16.5 glas
sphere 50 681.33 81.6 600 lite
EOF
if [ -n "${SMALLPT:-}" ] && [ -f "$SMALLPT" ]; then
    # 128 x 96, the output named by the second argument; a copy with other random numbers
    # for its converged image
    sed 's/int w=1024, h=768/int w=128, h=96/; s/fopen("image.ppm", "w")/fopen(argv[2], "w")/; s/argc==2 ? atoi/argc>=2 ? atoi/' \
        "$SMALLPT" >"$out/smallpt.cpp"
    sed 's/Xi\[3\]={0,0,y\*y\*y}/Xi[3]={1,7,y*y*y}/' "$out/smallpt.cpp" >"$out/smallpt_ref.cpp"
    g++ -O3 -w -o "$out/smallpt" "$out/smallpt.cpp"
    g++ -O3 -w -o "$out/smallpt_ref" "$out/smallpt_ref.cpp"
    rt="./ray $out/smallpt.scene --camera-ray slides"
    "$out/smallpt_ref" 4096 "$out/sp_ref.ppm" 2>/dev/null
    $rt --spp 4096 --seed 7 -o "$out/rt_ref.png"
    : >"$out/sp" && : >"$out/rt" && : >"$out/rta"
    for k in $(seq "$runs"); do
        build/double/rtbench time "$out/smallpt" 256 "$out/sp.ppm" >>"$out/sp" 2>/dev/null
        build/double/rtbench time $rt --spp 256 --threads 1 -o "$out/rt.png" >>"$out/rt"
        build/double/rtbench time $rt --spp 256 --threads 1 --sphere-lamps area -o "$out/rta.png" >>"$out/rta"
    done
    # sigma: the noise of one sample a pixel, each against its own converged image
    ssp=$(build/double/rtbench noise "$out/sp.ppm" gamma 256 "$out/sp_ref.ppm" gamma 4096)
    srt=$(build/double/rtbench noise "$out/rt.png" srgb 256 "$out/rt_ref.png" srgb 4096)
    srta=$(build/double/rtbench noise "$out/rta.png" srgb 256 "$out/rt_ref.png" srgb 4096)
    # time to equal noise: sigma^2 times the time, run by run
    paste "$out/rt" "$out/sp" | awk -v a="$srt" -v b="$ssp" '{ print a * a * $1 / (b * b * $2) }' >"$out/eq"
    paste "$out/rta" "$out/sp" | awk -v a="$srta" -v b="$ssp" '{ print a * a * $1 / (b * b * $2) }' >"$out/eqa"
    # smallpt's error against rt's converged image (its clamping and filter included), and the
    # samples rt needs for the same error: sigma^2 / (e^2 - the reference's own share)
    esp=$(build/double/rtbench noise "$out/sp.ppm" gamma 1 "$out/rt_ref.png" srgb 1e30)
    {
    echo
    echo "### smallpt's Cornell box, 128 x 96, 256 samples a pixel, one thread ($runs runs in turn)"
    echo
    echo "| program | ms | noise of one sample (linear light) |"
    echo "|---|---:|---:|"
    printf '| smallpt (g++ -O3) | %s | %.3f |\n' "$(spread "$out/sp")" "$ssp"
    printf '| ./ray --camera-ray slides | %s | %.3f |\n' "$(spread "$out/rt")" "$srt"
    printf '| ./ray ... --sphere-lamps area | %s | %.3f |\n' "$(spread "$out/rta")" "$srta"
    echo
    echo "- time to equal noise, rt against smallpt (noise^2 x time, run by run): $(median2 "$out/eq") (quartiles $(quartiles "$out/eq")); with --sphere-lamps area: $(median2 "$out/eqa") (quartiles $(quartiles "$out/eqa"))"
    awk -v e="$esp" -v s="$srt" -v t="$(median "$out/rt")" -v ts="$(median "$out/sp")" 'BEGIN {
        n = s * s / (e * e - s * s / 4096)
        printf "- smallpt at 256 samples is off rt'"'"'s converged image by %.4f (RMS, linear); rt reaches that at %.0f samples, %.2f of smallpt'"'"'s time\n", e, n, n / 256 * t / ts }'
    } >>"$report"
else
    echo "- smallpt: skipped (SMALLPT=path/to/smallpt.cpp make bench; https://www.kevinbeason.com/smallpt/)" >>"$report"
fi
echo "bench: smallpt done" >&2

# ---- the triangle search beside Embree, tinybvh and bvh v2 (bench/kernels.sh) ---------------
sh bench/kernels.sh "$out" "$report" "${KERNEL_RUNS:-9}"

# ---- spheres by the thousand: one list against the spheres' BVH -----------------------------
{
echo
echo "### Spheres: a ray's cost against their number (256 x 256, one thread, shadows, mirrors, glass)"
echo
echo "| spheres | list: render ms | BVH: render ms | rays | BVH: us a ray |"
echo "|---:|---:|---:|---:|---:|"
} >>"$report"
for n in 10 100 1000 10000 100000; do
    awk -v n="$n" 'BEGIN { srand(n); side = int(sqrt(n)); r = 4 / side
        print "size 256 256\ncamera lookat 0 2 12  0 0 0  0 1 0  40\nlight 5 10 5"
        print "material a diffuse 0.8 0.3 0.3\nmaterial b diffuse 0.3 0.8 0.3 mirror 0.5\nmaterial g glass 1.5"
        print "sphere 0 -1000 0 1000 a"
        for (i = 1; i < n; i++)
            printf "sphere %.5f %.5f %.5f %.5f %s\n", 10 * rand() - 5, 3 * rand(), 10 * rand() - 5,
                r * (0.3 + 0.7 * rand()), substr("abg", 1 + int(3 * rand()), 1) }' >"$out/spheres.scene"
    : >"$out/list.render" && : >"$out/tree.render"
    for k in $(seq "$runs"); do
        if [ "$n" -le 10000 ]; then timed list ./ray "$out/spheres.scene" --layout list --threads 1 --stats -o "$out/s.png"; fi
        timed tree ./ray "$out/spheres.scene" --layout bvh --threads 1 --stats -o "$out/s.png"
    done
    rays=$(cat "$out/tree.rays")
    listms="-"
    if [ "$n" -le 10000 ]; then listms=$(spread "$out/list.render"); fi
    echo "| $n | $listms | $(spread "$out/tree.render") | $rays | $(awk -v t="$(median "$out/tree.render")" -v r="$rays" 'BEGIN { printf "%.3f", t * 1000 / r }') |" >>"$report"
done
echo "bench: spheres done" >&2

# ---- copies of one triangle: where no split can help ----------------------------------------
{
echo
echo "### 10,000 copies of one triangle (256 x 256, one thread): the BVH against the list"
echo
} >>"$report"
awk 'BEGIN { print "size 256 256\ncamera lookat 0 0 5  0 0 0  0 1 0  40\nlight 5 10 5\nmaterial a diffuse 0.8 0.3 0.3"
    for (i = 0; i < 10000; i++) print "triangle -1 -1 0  1 -1 0  0 1 0 a" }' >"$out/copies.scene"
: >"$out/list.render" && : >"$out/tree.render"
for k in $(seq 3); do
    timed list ./ray "$out/copies.scene" --layout list --threads 1 --stats -o "$out/c.png"
    timed tree ./ray "$out/copies.scene" --layout bvh --threads 1 --stats -o "$out/c.png"
done
echo "- render ms: list $(spread "$out/list.render"), BVH $(spread "$out/tree.render"); the BVH's time over the list's: $(ratio "$out/tree.render" "$out/list.render")" >>"$report"
echo "bench: copies done" >&2
