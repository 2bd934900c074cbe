#!/bin/sh
# tools/grade.sh -- `make grade`: the grading scenes' reference set written into a private folder
# of this grading's own (build/grade-set: rt's images, and those of the tiny tracer with each
# bug), then the grader (build/grader) on one of:
#   TRACER=PROGRAM   runs `PROGRAM SCENE -o OUT.png` on each scene (a path with spaces is one
#                    program; otherwise the words are a program and its first arguments)
#   IMAGES=DIR       grades DIR/NAME.png (or .ppm), for a tracer with another command line
#   CLASS=DIR        builds each submission folder in DIR (each a kit) and grades it: marks.csv
#                    and a report each in OUT (default build/grade/class)
# SEED=N varies every scene (0, the default: the public scenes of scenes/grade/); TIME=S is the
# time a scene may take (default 10 seconds); REPORT=FILE writes a page for the student; JSON=FILE
# Gradescope's results.json. The steps handed out are tools/starter/stubs.list's.
set -u
seed=${SEED:-0}
steps=$(sed 's/#.*//; /^[ 	]*hints/d' tools/starter/stubs.list | tr -s ' \t\r\n' '    ')
set_dir=$(mktemp -d "${TMPDIR:-/tmp}/rt-set-XXXXXX") || exit 2
trap 'rm -rf "$set_dir"' EXIT
trap 'exit 2' INT TERM
build/grade-set "$set_dir" --seed "$seed" --steps "$steps" --tiny build/tiny || exit 2

# Where the reader finds the scenes, to follow a pixel with rt's --pixel
scenes=scenes/grade
if [ "$seed" != 0 ]; then
    scenes=build/grade/seed-$seed
    mkdir -p "$scenes" && cp "$set_dir"/*.scene "$scenes"/
fi
set -- "$set_dir" --time "${TIME:-10}" --follow "./ray $scenes/{scene}.scene --methods handout --pixel"
[ -n "${REPORT:-}" ] && set -- "$@" --report "$REPORT"
[ -n "${JSON:-}" ] && set -- "$@" --json "$JSON"

if [ -n "${CLASS:-}" ]; then
    kit=${KIT:-build/starter/rt-starter}
    [ -d "$kit" ] || sh tools/starter.sh build/starter >/dev/null || exit 2
    build/grader "$@" --class "$CLASS" --kit "$kit" --out "${OUT:-build/grade/class}" \
        --cxx "${CXX:-c++}" --cxxflags "$KIT_CXXFLAGS" --libs "$PNG_LIBS -pthread"
    exit $?
elif [ -n "${IMAGES:-}" ]; then
    build/grader "$@" --images "$IMAGES"
    exit $?
elif [ -n "${TRACER:-}" ]; then
    if [ -e "$TRACER" ]; then
        build/grader "$@" -- "$TRACER"
    else
        build/grader "$@" -- $TRACER
    fi
    exit $?
fi
echo "usage: make grade TRACER=PROGRAM | IMAGES=DIR | CLASS=DIR [SEED=N] [TIME=S]" >&2
exit 2
