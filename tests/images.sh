#!/bin/sh
# tests/images.sh DIR OUT [RUNNER]: renders every bundled scene with DIR/ray and DIR/ray_float
# into OUT (small, one thread, plain and jittered, and the handouts' methods), so that builds
# made with other compilers, kernels or processors can be compared byte for byte:
#     sh tests/images.sh . build/images/native
#     make RT_SCALAR=1 && sh tests/images.sh . build/images/scalar
#     diff -r build/images/native build/images/scalar && echo identical
# RUNNER runs a program built for another processor, for example `qemu-aarch64`.
set -eu
dir=$1
out=$2
runner=${3:-}
mkdir -p "$out"
# draw PROGRAM: every scene with DIR/PROGRAM (the two programs draw at once, a core each: under
# an emulator each image takes a while)
draw() {
    program=$1
    for scene in default test scenes/*.scene; do
        name=$(basename "$scene" .scene)
        size=96 spp=4
        case $name in # (a screen-corner camera keeps its screen's shape)
        cornell | assignment_path) size=48 spp=16 ;;
        handout2) size=128x96 ;;
        effects) size=160x100 ;;
        esac
        run() { $runner "$dir/$program" "$scene" --size $size --threads 1 "$@" >/dev/null; }
        run -o "$out/${program}_$name.png"
        run --spp $spp --aa jitter -o "$out/${program}_${name}_jitter.png"
        run --methods handout -o "$out/${program}_${name}_handout.png"
    done
}
draw ray &
double=$!
draw ray_float &
float=$!
wait $double
wait $float
echo "$(ls "$out" | wc -l | tr -d ' ') images in $out"
