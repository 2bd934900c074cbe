#!/bin/sh
# A class graded as a teacher grades it (make grade CLASS=DIR, tools/grade/build.cpp), and on
# Gradescope: its bundle (build/starter/gradescope), with run_autograder run here in a scratch
# root standing for the container's /autograder. (The kit's GitHub Classroom workflow is run in
# tests/starter.sh, where a solved kit is built.) Submissions: a solved kit, one with a bug, one that does not build, and an
# empty folder. Ends with `N passed, M failed`.
set -u
passed=0 failed=0
check() { # check STATUS TEXT: STATUS 0 passes
    if [ "$1" -eq 0 ]; then passed=$((passed + 1)); else failed=$((failed + 1)) && echo "tests/class.sh: FAILED $2"; fi
}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fast="-O0 -std=c++17 -w -ffp-contract=off -fno-math-errno -pthread $(pkg-config --cflags libpng 2>/dev/null)"

SEED=5 sh tools/starter.sh "$work/made" >/dev/null 2>"$work/made.err"
check $? "tools/starter.sh writes the kit and the bundle: $(cat "$work/made.err")"
sh tools/starter.sh "$work/solved" --solved >/dev/null 2>&1
class=$work/class
mkdir -p "$class/dave"
cp -R "$work/solved/rt-starter" "$class/alice"
cp -R "$work/solved/rt-starter" "$class/bob"
cp -R "$work/solved/rt-starter" "$class/carol"
sed -i.orig 's/real t = (-B - std::sqrt(discriminant))/real t = (-B + std::sqrt(discriminant))/' "$class/bob/geometry.cpp"
! cmp -s "$class/bob/geometry.cpp" "$class/bob/geometry.cpp.orig"
check $? "bob's kit takes the far root (the sphere stub's line is where the test expects it)"
printf 'this is not C++\n' >>"$class/carol/shade.cpp"

out=$(CLASS=$class KIT=$work/made/rt-starter OUT=$work/marks CXX="${CXX:-g++}" KIT_CXXFLAGS="$fast" \
    PNG_LIBS="$(pkg-config --libs libpng 2>/dev/null || echo -lpng)" sh tools/grade.sh 2>&1)
check $? "make grade CLASS=DIR grades the class: $out"
csv=$work/marks/marks.csv
n=$(head -n 1 "$csv" | tr ',' '\n' | grep -vc '^student$\|^passed$\|^total$')
grep -q "^alice,.*,$n,$n\$" "$csv"
check $? "alice's solved kit passes every scene: $(grep alice "$csv")"
grep -q "^bob,.*differs.*,$((n - 2)),$n\$" "$csv" || grep -q "^bob,.*differs.*,$((n - 1)),$n\$" "$csv"
check $? "bob's far root fails its scene: $(grep bob "$csv")"
grep -q "FAIL  far_root: .*looks like the sphere takes the far root" "$work/marks/bob.txt"
check $? "bob's report names the far root: $(grep far_root "$work/marks/bob.txt")"
grep -q "^carol,not-built,.*,0,$n\$" "$csv" && grep -q "does not build: shade.cpp: .*error" "$work/marks/carol.txt"
check $? "carol's kit does not build, and her report gives the compiler's error: $(head -n 1 "$work/marks/carol.txt")"
grep -q "^dave,.*,$n\$" "$csv" && [ -s "$work/marks/dave.html" ]
check $? "an empty folder is graded as the kit it lacks: $(grep dave "$csv")"
for s in alice bob carol dave; do
    [ -s "$work/marks/$s.html" ] && [ -s "$work/marks/$s.txt" ]
    check $? "$s has a report to read"
done
printf '%s\n' "$out" | grep -q "^4 submissions: "
check $? "the class is reported as a whole: $out"

# Gradescope: the bundle built and run_autograder run for a submission, as the container would
bundle=$work/made/gradescope
for f in setup.sh run_autograder build.sh seed.txt set/scenes.txt kit/ray.h; do
    [ -e "$bundle/$f" ]
    check $? "the Gradescope bundle has $f"
done
[ "$(cat "$bundle/seed.txt")" = 5 ] && ! cmp -s "$bundle/set/camera.scene" scenes/grade/camera.scene
check $? "the bundle grades on the scenes of its seed, not the public ones"
(cd "$bundle" && OPT=-O0 CXXFLAGS=-O0 CXX="${CXX:-g++}" sh build.sh >"$work/bundle.log" 2>&1)
check $? "the bundle's build.sh builds the grader: $(tail -3 "$work/bundle.log")"
for s in alice bob carol; do
    root=$work/root-$s
    mkdir -p "$root/results" && ln -s "$bundle" "$root/source" && cp -R "$class/$s" "$root/submission"
    AUTOGRADER_ROOT=$root CXX="${CXX:-g++}" sh "$bundle/run_autograder" >"$root/stdout" 2>&1
    json=$root/results/results.json
    [ "$(grep -c '"max_score": 1' "$json")" -eq "$(wc -l <"$bundle/set/scenes.txt")" ] &&
        grep -q '"visibility": "visible"' "$json" && grep -q '"output": ' "$json"
    check $? "run_autograder writes results.json in Gradescope's format for $s: $(head -c 300 "$json")"
done
! grep -q '"status": "failed"' "$work/root-alice/results/results.json"
check $? "alice passes every test on Gradescope"
grep -q '"name": "far_root", "score": 0' "$work/root-bob/results/results.json"
check $? "bob fails the far root on Gradescope"
grep -q 'does not build' "$work/root-carol/results/results.json"
check $? "carol is told her kit does not build"

echo "$passed passed, $failed failed"
