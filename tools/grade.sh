#!/bin/sh
# tools/grade.sh TRACER | --images DIR -- grades a ray tracer on the grading scenes
# (scenes/grade/*.scene), each made to reveal one classic bug (its "# reveals:" line). `make grade
# TRACER=PROGRAM` runs `PROGRAM SCENE -o OUT.png` on each; `make grade IMAGES=DIR` reads
# DIR/NAME.png (or .ppm) instead, for a tracer with another command line.
#
# Each image is compared with rt's own under the handouts' methods (`ray --methods handout`):
# a channel off by at most 4 of 255 counts as equal (a float tracer, or another rounding), and
# a scene passes when at most 1 pixel in 200 differs more. A scene that fails is compared with the
# images of the same scene drawn by a tracer with each known bug (tests/grade/tiny.cpp, --bug),
# and the nearest one names the bug. One line a scene; exit 0 only when every scene passes.
set -u
tracer="" images=""
case ${1:-} in
--images) images=${2:?"tools/grade.sh --images DIR"} ;;
"") echo "usage: tools/grade.sh TRACER | --images DIR" >&2 && exit 2 ;;
*) tracer=$1 ;;
esac
ray=./ray tiny=build/tiny out=build/grade
mkdir -p "$out/reference" "$out/bugs" "$out/images"
bugs="normals acne beyond reflect far-root no-limit upside-down mirrored edges"

# What each bug looks like and what to do about it, as the handouts put it.
advice() {
    case $1 in
    normals) echo "normals not turned toward the viewer: a light behind a triangle lights its front (if N.D > 0, N = -N)" ;;
    acne) echo "shadow acne: a shadow ray hits the surface it starts on (start it 1e-4 along, or skip that shape)" ;;
    beyond) echo "a shadow ray counts a blocker beyond the light (with D = light - P, only 0 < t < 1 blocks)" ;;
    reflect) echo "the reflection has the wrong sign (R = D - 2 (D.N) N)" ;;
    far-root) echo "the far root of the quadratic (take the least non-negative one)" ;;
    no-limit) echo "no limit on the chain of rays (at most 10 rays in a chain, the 11th black)" ;;
    upside-down) echo "the screen is upside down (pixel rows go down, the screen's y goes up)" ;;
    mirrored) echo "the screen is mirrored left to right" ;;
    edges) echo "rays slip through the edges triangles share (beta >= 0, gamma >= 0, beta + gamma <= 1)" ;;
    esac
}

if [ "$tracer" = --advice ]; then # (for the tests: what the grader says of bug $2)
    advice "${2:-}"
    exit 0
fi

# over A B: how many pixels of B differ from A by more than the tolerance ("" if unreadable).
over() {
    "$ray" --compare "$1" "$2" --tolerance 4 2>/dev/null |
        sed -n 's/^pixels over tolerance [0-9.]*: \([0-9]*\) of.*/\1/p'
}

# nearest SCENE NAME IMAGE ALLOWED: the bug whose image of the scene IMAGE matches, if any.
nearest() {
    best="" fewest=""
    for bug in $bugs; do
        "$tiny" --bug "$bug" "$1" -o "$out/bugs/$2-$bug.png" || continue
        n=$(over "$out/bugs/$2-$bug.png" "$3")
        if [ -n "$n" ] && [ "$n" -le "$4" ] && { [ -z "$fewest" ] || [ "$n" -lt "$fewest" ]; }; then
            best=$bug fewest=$n
        fi
    done
    echo "$best"
}

failed=0
for scene in scenes/grade/*.scene; do
    name=$(basename "$scene" .scene)
    reference=$out/reference/$name.png
    "$ray" "$scene" --methods handout -o "$reference" || exit 2
    if [ -n "$tracer" ]; then
        image=$out/images/$name.png
        rm -f "$image"
        $tracer "$scene" -o "$image" >/dev/null 2>&1
        status=$?
        if [ $status -ne 0 ] || [ ! -s "$image" ]; then
            echo "FAIL  $name: the tracer exited with status $status and no image (a chain of rays with no limit ends when the stack overflows)"
            failed=$((failed + 1))
            continue
        fi
    else
        image=$images/$name.png
        [ -f "$image" ] || image=$images/$name.ppm
    fi
    report=$("$ray" --compare "$reference" "$image" --tolerance 4 2>&1)
    count=$(printf '%s\n' "$report" | sed -n 's/^pixels over tolerance [0-9.]*: \([0-9]*\) of \([0-9]*\).*/\1 \2/p')
    if [ -z "$count" ]; then
        echo "FAIL  $name: the image cannot be compared with rt's ($(printf '%s\n' "$report" | tail -n 1))"
        failed=$((failed + 1))
        continue
    fi
    set -- $count
    allowed=$(($2 / 200))
    if [ "$1" -le "$allowed" ]; then
        echo "pass  $name"
        continue
    fi
    failed=$((failed + 1))
    worst=$(printf '%s\n' "$report" | sed -n 's/^  \([0-9]*\) \([0-9]*\):.*/(\1, \2)/p' | head -n 3 | tr '\n' ' ')
    bug=$(nearest "$scene" "$name" "$image" "$allowed")
    if [ -n "$bug" ]; then
        looks="looks like $(advice "$bug")"
    else
        looks="unlike every bug the grader knows ($(sed -n 's/^# reveals: //p' "$scene") is what the scene is made for)"
    fi
    first=$(printf '%s\n' "$report" | sed -n 's/^  \([0-9]*\) \([0-9]*\):.*/\1 \2/p' | head -n 1)
    echo "FAIL  $name: $1 of $2 pixels differ, the worst at ${worst% }: $looks (follow one: $ray $scene --methods handout --pixel $first)"
done
[ $failed -eq 0 ]
