#!/bin/sh
# tools/starter.sh DIR [--solved] [--with-wings] -- writes the student kit, DIR/rt-starter and
# DIR/rt-starter.tar.gz, and Gradescope's autograder, DIR/gradescope and DIR/autograder.zip
# (`make starter`; SEED=N chooses the autograder's scenes): rt's teaching core and app/ as given code, with the
# functions tools/starter/stubs.list names replaced by stubs (tools/starter/stubs.txt, or
# STUBS_TXT), and without the robust/ and fast/ wings: the statements marked `// robust/: ...`
# or `// fast/: ...` left out, and the functions stubs.txt names replaced, found by name
# (tools/starter/regions.awk). The kit is made from the very code rt tests; a name in stubs.txt
# that rt no longer defines stops it.
# --solved keeps rt's bodies in place of the stubs (the kit's checks must then all pass), and
# writes no Gradescope bundle.
# --reading writes the reading edition into DIR itself (`make reading`): solved, every step's
# checks, no grader, no bundle.
# --with-wings keeps robust/ and fast/ (for a teacher who asks for them): the kit then runs rt's
# robust methods by default, and the handouts' under --methods handout.
set -eu
out=$1
shift
solved=0 wings=0 reading=0
for option in "$@"; do
    case $option in
    --solved) solved=1 ;;
    --reading) solved=1 reading=1 ;;
    --with-wings) wings=1 ;;
    *) echo "tools/starter.sh: unknown option $option" >&2 && exit 2 ;;
    esac
done
kit=$out/rt-starter
[ $reading = 1 ] && kit=$out
# stubs.list (or STUBS_LIST): step names (each exactly one of stubs.txt's sections), `#`
# comments, and at most one line `hints formula|steps|none` (HINTS=... overrides it): how much
# the stubs' comments say (stubs.txt). Anything else is refused, naming the line.
list=${STUBS_LIST:-tools/starter/stubs.list}
stubs_txt=${STUBS_TXT:-tools/starter/stubs.txt}
steps=$(sed -n 's/^@@ \([^ ]*\).*/\1/p' "$stubs_txt" | grep -v '^kit-' | tr '\n' ' ')
parsed=$(awk -v steps=" $steps" -v file="$list" '
    { sub(/\r$/, ""); sub(/#.*/, "") }
    NF == 0 { next }
    $1 == "hints" {
        if (NF != 2 || $2 !~ /^(formula|steps|none)$/) {
            print file ":" NR ": `hints formula`, `hints steps` or `hints none`" > "/dev/stderr"; bad = 1
        }
        hints = $2; next
    }
    {
        for (i = 1; i <= NF; i++)
            if (index(steps " ", " " $i " ") == 0) {
                print file ":" NR ": no step named \"" $i "\" (the steps:" steps ")" > "/dev/stderr"; bad = 1
            } else list = list " " $i
    }
    END { if (bad) exit 2; print (hints == "" ? "formula" : hints) list }
' "$list") || exit 2
hints=${HINTS:-${parsed%% *}}
case $hints in formula | steps | none) ;; *) echo "HINTS=$hints: formula, steps or none" >&2 && exit 2 ;; esac
stubs=" ${parsed#* } "
[ "$parsed" = "${parsed#* }" ] && stubs=" "
rm -rf "$kit"
mkdir -p "$kit/app" "$kit/tests" "$kit/scenes"
case $stubs in *" plane "*) case $stubs in *" cramer "*) plane=0 ;; *) plane=1 ;; esac ;; *) plane=0 ;; esac
found=$kit/.found # (each name of stubs.txt that a source defines, a line each time)
: >"$found"
region() {
    awk -v stubs="$stubs" -v solved=$solved -v wings=$wings -v hints="$hints" -v plane=$plane \
        -v found="$found" -f tools/starter/regions.awk "$stubs_txt" "$1" >"$kit/$1"
}
for file in ray.h ray.cpp camera.cpp blur.cpp geometry.cpp shade.cpp smooth.cpp render.cpp render.h \
    path.cpp path_full.cpp path.h path_sampling.h numbers.h scene_*.cpp app/*.h app/*.cpp \
    tests/test.h tests/test_handout.h tests/test_handout.cpp tests/test_handout_light.cpp \
    tests/kit_main.cpp; do
    region "$file"
done
# Each name a section gives must be defined once (else rt renamed it, and the kit would keep rt's
# body or code that a kit leaves out), and a `mark` section's function must hold a mark.
awk -v txt="$stubs_txt" 'FNR == NR { count[$0]++; next }
    /^@@ / {
        what = ($2 ~ /^kit-/ ? "section " : "step ") $2
        for (i = 4; i <= NF; i++) {
            n = count[$i] + 0
            m = count[$i " mark"] + 0
            if (n != 1)
                why = n == 0 ? "which no source of the kit defines" : "defined " n " times"
            else if ($3 == "mark" && m == 0)
                why = "which has no statement marked // robust/: or // fast/:"
            else
                continue
            print "tools/starter.sh: " txt ": " what " names " $i ", " why >"/dev/stderr"
            bad = 1
        }
    }
    END { exit bad }' "$found" "$stubs_txt" || exit 2
rm -f "$found"
if [ $wings = 1 ]; then
    mkdir -p "$kit/robust" "$kit/fast"
    cp robust/*.cpp robust/*.h "$kit/robust/" && cp fast/*.cpp fast/*.h "$kit/fast/"
fi
cp scenes/*.scene scenes/*.obj "$kit/scenes/"
cp tools/starter/Makefile tools/starter/README.md .clang-format LICENSE "$kit/"
tr -d '\r' <"$list" >"$kit/stubs.list"
if [ $reading = 1 ]; then # (every step's checks, no grader, no bundle)
    cp tools/starter/READING.md "$kit/README.md"
    echo "$steps" | tr ' ' '\n' | sed '/^$/d' >"$kit/stubs.list"
    echo "$kit/: the reading edition, every step solved, without robust/ and fast/"
    exit 0
fi

# What a student checks an image against: rt's image of each bundled scene under the handouts'
# methods (made by `make starter`), and the grader with the public grading scenes (seed 0).
mkdir -p "$kit/references" "$kit/grade" "$kit/.github/workflows"
cp build/references/*.png "$kit/references/"
cp tools/grade/grade.h tools/grade/main.cpp tools/grade/run.cpp tools/grade/judge.cpp \
    tools/grade/grade.cpp tools/grade/report.cpp tools/grade/build.cpp tools/grade/set_read.cpp "$kit/grade/"
build/grade-set "$kit/grade/set" --steps "$stubs" --tiny build/tiny
sh tools/starter/workflow.sh "$kit/grade/set" >"$kit/.github/workflows/classroom.yml"
(cd "$out" && tar czf rt-starter.tar.gz rt-starter)

echo "$kit/ and $out/rt-starter.tar.gz: the kit, with stubs for:$stubs"
[ $solved = 1 ] && exit 0 # (no Gradescope bundle: its kit would hold the answers)

# Gradescope's bundle: the kit (what a submission lacks, and the grader's sources), the grading
# scenes varied by SEED (a new one each time unless given: keep it to grade the same way again).
seed=${SEED:-$(od -An -N4 -tu4 /dev/urandom | tr -d ' ')}
bundle=$out/gradescope
rm -rf "$bundle" "$out/autograder.zip"
mkdir -p "$bundle"
cp -R "$kit" "$bundle/kit"
cp tools/starter/gradescope/setup.sh tools/starter/gradescope/build.sh \
    tools/starter/gradescope/run_autograder "$bundle/"
build/grade-set "$bundle/set" --seed "$seed" --steps "$stubs" --tiny build/tiny
echo "$seed" >"$bundle/seed.txt"
zipped="$out/autograder.zip"
if command -v zip >/dev/null; then
    (cd "$bundle" && zip -qr ../autograder.zip .)
elif command -v python3 >/dev/null; then
    (cd "$bundle" && python3 -m zipfile -c ../autograder.zip setup.sh run_autograder build.sh seed.txt kit set)
else
    zipped="(no zip or python3 here: zip the files inside $bundle, not the folder)"
fi
echo "$zipped: Gradescope's autograder, grading scenes of seed $seed (keep it to grade the same way again)"
