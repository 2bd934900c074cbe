#!/bin/sh
# bench/weekend.sh [RUNS]: rt beside Ray Tracing in One Weekend's own program on the book's final
# scene (scenes/weekend.scene), at equal error, into build/bench/weekend.md (bench.sh runs it and
# adds the table to speed.md). The book's code is not part of rt:
#     git clone https://github.com/RayTracing/raytracing.github.io
#     RTIOW=path/to/raytracing.github.io make bench
# Without it the row says so and how to get it, as the smallpt row does.
#
# Method. Both programs draw the same scene at 160 x 90, 50 rays a path, on one thread, each run
# in turn with the other. The book's program is its src/InOneWeekend, built with g++ -O3 from a
# copy changed by sed in five places: the width (160: the book's 16:9 makes it 90 high); the
# samples a pixel and a seed (srand, after the scene is built, so the scene stays the book's)
# from the command line; max_depth 50, as the book's text has it (its sample code, 20); and the
# metal's fuzz drawn on the fuzz sphere (random_unit_vector), as the text has it and rt does (the
# sample code draws inside the ball). A copy that prints the spheres' numbers instead of
# rendering must print what tools/weekend_scene.cpp prints (the scene is the book's). rt runs
# with --fresnel schlick, the book's Fresnel: with its defaults, and with --roulette off.
#
# An image's error is its RMS difference from a converged reference (rt at REF samples with
# another seed), in linear light (the book's pixels decoded by its square-root curve, rt's by
# sRGB), over every channel. For each of the book's sample counts N (10, its sample code's; 100,
# its chapters'; 500, its final render's): the book's error e at N; rt's noise of one sample,
# sigma, from a pilot render; the samples rt needs for error e, n = sigma^2 / (e^2 - sigma^2 /
# REF); then the book at N and rt at n (for each of its two settings) run in turn, RUNS times,
# each one timed (whole process) and its error measured. Beside them: the book's own noise (two
# seeds) and what its converged image differs from rt's beyond that noise.
set -eu
runs=${1:-3}
W=160 H=90
REF=${WEEKEND_REF:-4096}
COUNTS=${WEEKEND_COUNTS:-10 100 500}
dir=build/bench
mkdir -p "$dir"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
md=$dir/weekend.md
. bench/stats.sh

skip() {
    printf '\n### Ray Tracing in One Weekend'"'"'s final scene, at equal error\n\n- skipped: %s\n' "$1" >"$md"
    echo "bench: weekend skipped" >&2
    exit 0
}
src=${RTIOW:-}/src/InOneWeekend
[ -n "${RTIOW:-}" ] && [ -f "$src/main.cc" ] ||
    skip "the book's program (git clone https://github.com/RayTracing/raytracing.github.io; RTIOW=path/to/raytracing.github.io make bench)"
book=$out/book
mkdir -p "$book"
cp "$src"/*.h "$src"/main.cc "$book/"
sed -e 's/^int main() {/int main(int argc, char **argv) {/' \
    -e "s/cam.image_width *= *[0-9]*;/cam.image_width = $W;/" \
    -e 's/cam.samples_per_pixel *= *[0-9]*;/cam.samples_per_pixel = atoi(argv[1]);/' \
    -e 's/cam.max_depth *= *[0-9]*;/cam.max_depth = 50;/' \
    -e 's/cam.render(world);/std::srand(atoi(argv[2])); cam.render(world);/' \
    "$book/main.cc" >"$book/bench.cc"
sed 's/fuzz\*random_in_unit_sphere()/fuzz*random_unit_vector()/' "$src/material.h" >"$book/material.h"
# the copy that prints the small spheres' numbers, as build/weekend_scene numbers prints them
sed -e 's/\(auto albedo = color::random() \* color::random();\)/\1 printf("D %.17g %.17g %.17g\\n", albedo.x(), albedo.y(), albedo.z());/' \
    -e 's/\(auto fuzz = random_double(0, 0.5);\)/\1 printf("M %.17g %.17g %.17g %.17g\\n", albedo.x(), albedo.y(), albedo.z(), fuzz);/' \
    -e 's/\(sphere_material = make_shared<dielectric>(1.5);\)/\1 printf("G\\n");/' \
    -e 's/\(world.add(make_shared<sphere>(center, 0.2, sphere_material));\)/\1 printf("C %.17g %.17g\\n", center.x(), center.z());/' \
    -e 's/cam.render(world);/return 0;/' \
    "$book/main.cc" >"$book/numbers.cc"
for change in "image_width = $W;" 'atoi(argv\[1\])' 'max_depth = 50;' 'std::srand'; do
    grep -q "$change" "$book/bench.cc" || skip "the book's main.cc has changed: no '$change' after the edits (bench/weekend.sh)"
done
grep -q 'fuzz\*random_unit_vector()' "$book/material.h" ||
    skip "the book's material.h has changed: its metal's fuzz could not be put on the sphere"
g++ -O3 -w -o "$book/book" "$book/bench.cc"
g++ -O3 -w -include cstdio -o "$book/numbers" "$book/numbers.cc"
"$book/numbers" >"$out/book_numbers.txt" 2>/dev/null
build/weekend_scene numbers >"$out/rt_numbers.txt"
cmp -s "$out/book_numbers.txt" "$out/rt_numbers.txt" ||
    skip "the book's program draws other spheres than tools/weekend_scene.cpp (another C library's rand()?)"
build/weekend_scene | cmp -s - scenes/weekend.scene ||
    skip "scenes/weekend.scene is not what build/weekend_scene writes"

rt="./ray scenes/weekend.scene --size ${W}x$H --fresnel schlick"
$rt --spp "$REF" --seed 7 -o "$out/ref.png"
echo "bench: weekend reference done" >&2
# error IMAGE CURVE: its RMS difference from the reference, linear light
error() { build/double/rtbench noise "$1" "$2" 1 "$out/ref.png" srgb 1e30; }

# pilot OPTIONS: rt's noise of one sample with these options, from a render at n samples, and the
# samples it needs for error e, n = sigma^2 / (e^2 - sigma^2 / REF): "sigma samples"
pilot() {
    $rt $1 --spp "$n" --threads 1 -o "$out/pilot.png"
    s=$(build/double/rtbench noise "$out/pilot.png" srgb "$n" "$out/ref.png" srgb "$REF")
    awk -v s="$s" -v e="$e" -v r="$REF" 'BEGIN { d = e * e - s * s / r; n = d > 0 ? s * s / d : 65536
        n = int(n) + (n > int(n)); printf "%s %d\n", s, (n > 65536 ? 65536 : (n < 1 ? 1 : n)) }'
}
# row LABEL SAMPLES TIMES IMAGE: a row of the table for one of rt's settings
row() {
    printf '| %s | %s | %.4f | %s | %s | %s | %.4f | %s |\n' "$n" "$(spread "$out/bt")" "$e" "$1" "$2" \
        "$(spread "$3")" "$(error "$4" srgb)" "$(ratio "$3" "$out/bt")" >>"$md"
}

{
echo
echo "### Ray Tracing in One Weekend's final scene, at equal error"
echo
echo "$W x $H, 50 rays a path, one thread, $runs runs in turn; error: RMS against rt at $REF samples (another seed), linear light. rt: \`./ray scenes/weekend.scene --fresnel schlick --threads 1\` with its defaults, and with \`--roulette off\`; the book: its program, \`g++ -O3\`."
echo
echo "| the book's samples | the book, ms | its error | rt | rt's samples for that error | rt, ms | rt's error | rt's time over the book's |"
echo "|---:|---:|---:|---|---:|---:|---:|---:|"
} >"$md"
notes=""
for n in $COUNTS; do
    # The book's error at n, and its own noise: a second seed
    : >"$out/bt" && : >"$out/ra" && : >"$out/rb"
    "$book/book" "$n" 2 >"$out/b2.ppm" 2>/dev/null
    build/double/rtbench time /bin/sh -c "'$book/book' $n 1 >'$out/b1.ppm' 2>/dev/null" >>"$out/bt"
    e=$(error "$out/b1.ppm" sqrt)
    own=$(build/double/rtbench noise "$out/b1.ppm" sqrt 1 "$out/b2.ppm" sqrt 1)
    set -- $(pilot "")
    sa=$1 ma=$2
    set -- $(pilot "--roulette off")
    sb=$1 mb=$2
    for k in $(seq "$runs"); do # (the book's first run is timed above)
        [ "$k" = 1 ] ||
            build/double/rtbench time /bin/sh -c "'$book/book' $n 1 >'$out/b1.ppm' 2>/dev/null" >>"$out/bt"
        build/double/rtbench time $rt --spp "$ma" --threads 1 -o "$out/ra.png" >>"$out/ra"
        build/double/rtbench time $rt --roulette off --spp "$mb" --threads 1 -o "$out/rb.png" >>"$out/rb"
    done
    row "defaults" "$ma" "$out/ra" "$out/ra.png"
    row "--roulette off" "$mb" "$out/rb" "$out/rb.png"
    # The book's own noise at n (rtbench noise takes the two seeds' difference as sqrt 2 times
    # it), the reference's, and what is left of e beyond both: the converged images' difference
    notes="$notes$(awk -v n="$n" -v e="$e" -v b="$own" -v s="$sa" -v r="$REF" 'BEGIN {
        left = e * e - b * b - s * s / r
        printf "- at %d samples the book'"'"'s own noise is %.4f (two seeds), the reference'"'"'s %.4f; what is left of its error beyond them, %.4f, is how far its converged image is from rt'"'"'s", n, b, s / sqrt(r), (left > 0 ? sqrt(left) : 0) }')
"
    echo "bench: weekend at $n samples done" >&2
done
{
echo
printf '%s' "$notes"
echo "- noise of one sample (linear light): rt $(printf '%.3f' "$sa"), rt --roulette off $(printf '%.3f' "$sb"), the book $(awk -v b="$own" -v n="$n" 'BEGIN { printf "%.3f", b * sqrt(n) }') (from the last row's pilots and seeds)"
} >>"$md"
cat "$md" >&2
