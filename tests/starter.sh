#!/bin/sh
# The starter kit (`make starter`, tools/starter.sh) as a student and a teacher meet it: unpacked
# from its .tar.gz on its own, it builds with no warning, draws the assignment's background, and
# its `make test` fails on the stubs with the handouts' advice; with rt's bodies in place of the
# stubs (--solved) it builds with no warning, passes every check, and draws rt's own image under
# the handouts' methods, byte for byte; and a kit that keeps robust/ and fast/ (--with-wings),
# solved, draws rt's own default image. Ends with `N passed, M failed`.
set -u
passed=0 failed=0
check() { # check STATUS TEXT: STATUS 0 passes
    if [ "$1" -eq 0 ]; then passed=$((passed + 1)); else failed=$((failed + 1)) && echo "tests/starter.sh: FAILED $2"; fi
}
root=$(pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# kitmake DIR ARGS: make in a kit, with the compiler rt's make test was given ($CXX), on its own
# (MAKEFLAGS cleared: not a part of rt's make), quickly (-O0)
kitmake() {
    dir=$1
    shift
    (cd "$dir" && MAKEFLAGS= make CXX="${CXX:-g++}" CXXFLAGS=-O0 "$@")
}
build() { kitmake "$1" >"$1/build.log" 2>&1; }

sh tools/starter.sh "$work/made" >/dev/null 2>"$work/made.err"
check $? "tools/starter.sh writes the kit: $(cat "$work/made.err")"
mkdir -p "$work/student" && (cd "$work/student" && tar xzf "$work/made/rt-starter.tar.gz")
kit=$work/student/rt-starter
build "$kit"
check $? "the kit builds from its .tar.gz: $(tail -5 "$kit/build.log")"
! grep -q "warning:" "$kit/build.log"
check $? "the kit builds with no warning: $(grep "warning:" "$kit/build.log" | head -3)"
for wing in robust fast; do
    [ ! -e "$kit/$wing" ] && ! grep -q "#include \".*$wing/" "$kit"/*.cpp "$kit"/*.h "$kit"/app/*
    check $? "the kit has no $wing/ and includes nothing from it"
done
printf 'P6\n512 512\n255\n' >"$work/black.ppm" && head -c 786432 /dev/zero >>"$work/black.ppm"
(cd "$kit" && ./ray >/dev/null 2>&1 && "$root/ray" --compare reference.png "$work/black.ppm" >/dev/null)
check $? "./ray in the kit draws the assignment's background, black, on the first day"
out=$(kitmake "$kit" test 2>&1)
status=$?
last=$(printf '%s\n' "$out" | grep -E '^[0-9]+ passed, [0-9]+ failed$' | tail -n 1)
case $last in *" passed, "*" failed") r=0 ;; *) r=1 ;; esac
check $r "the kit's make test ends with N passed, M failed: $last"
[ $status -ne 0 ] && [ "${last#* passed, 0 failed}" = "$last" ]
check $? "the kit's make test fails on the stubs: $last"
printf '%s\n' "$out" | grep -q "you report t = \|you report no hit: check B = 2 d.(o - c)"
check $? "a failing check of the sphere says what it should give, what came, and the likely cause"
printf '%s\n' "$out" | grep -q "fix sphere first: its checks fail"
check $? "on the first day the shadow's checks say to fix the sphere first, not the shadow"

# The kit speaks of itself: its help, its first-day warning, and its stubs' hints
help=$(cd "$kit" && ./ray --help)
printf '%s\n' "$help" | grep -q "the kit's only set" && ! printf '%s\n' "$help" | grep -q "robust ones (default)"
check $? "the kit's --help gives the kit's methods, not rt's: $(printf '%s\n' "$help" | grep -A1 -- --methods)"
warning=$(cd "$kit" && ./ray -o "$work/first.png" 2>&1)
printf '%s\n' "$warning" | grep -q "the stubs are not written yet"
check $? "the first day's warning speaks of the stubs: $warning"
grep -q "B = 2 d.(o - c)" "$kit/geometry.cpp" && ! grep -q "sqrt(B^2 - 4AC)" "$kit/geometry.cpp" &&
    ! grep -q "AnyHitFrom(scene, methods, &ray" "$kit/geometry.cpp"
check $? "by default a stub gives the handout's formula, not the code (hints formula)"
HINTS=steps sh tools/starter.sh "$work/steps" >/dev/null 2>&1
grep -q "sqrt(B^2 - 4AC)" "$work/steps/rt-starter/geometry.cpp" &&
    grep -q "AnyHitFrom(scene, methods, &ray" "$work/steps/rt-starter/geometry.cpp"
check $? "HINTS=steps gives the steps, call by call"
HINTS=none sh tools/starter.sh "$work/none" >/dev/null 2>&1
grep -q "Your code: the slide's sphere." "$work/none/rt-starter/geometry.cpp" &&
    ! grep -q "The hit is the least root t with tMin < t < tMax" "$work/none/rt-starter/geometry.cpp"
check $? "HINTS=none names the step alone"

# stubs.list lines that name no step are refused, naming the line; CR LF lines are read
for bad in "sph.re" "*" "sphere spheer" "hints lots"; do
    printf 'get-ray\n%s\n' "$bad" >"$work/bad.list"
    err=$(STUBS_LIST=$work/bad.list sh tools/starter.sh "$work/bad" 2>&1 >/dev/null)
    status=$?
    [ $status -ne 0 ] && printf '%s\n' "$err" | grep -q "bad.list:2: "
    check $? "a stubs.list line \`$bad\` is refused, naming its line: $err"
done
printf 'get-ray\r\nsphere # the quadratic\r\n' >"$work/crlf.list"
STUBS_LIST=$work/crlf.list sh tools/starter.sh "$work/crlf" >/dev/null 2>&1 &&
    grep -q "Your code: the slide's sphere" "$work/crlf/rt-starter/geometry.cpp"
check $? "a stubs.list with CR LF line ends is read"

# A function of stubs.txt renamed in rt stops the kit, naming the function and its step (else the
# kit would hand out rt's body as the stub); so does a `mark` section whose function has no mark
tree=$work/tree
mkdir -p "$tree/tests" && cp -R ./*.cpp ./*.h app tools "$tree/" &&
    cp tests/test.h tests/test_handout.h tests/test_handout.cpp tests/test_handout_light.cpp \
        tests/kit_main.cpp "$tree/tests/"
sed 's/FloorColor(/FloorShade(/' shade.cpp >"$tree/shade.cpp"
err=$(cd "$tree" && sh tools/starter.sh "$work/renamed" --reading 2>&1 >/dev/null)
status=$?
[ $status -ne 0 ] && printf '%s\n' "$err" | grep "step floor" | grep -q "FloorColor"
check $? "a step's function renamed in rt stops the kit, naming it: $err"
sed 's/^@@ kit-hit-triangle mark HitTriangle$/@@ kit-hit-triangle mark FindNearestHit/' \
    tools/starter/stubs.txt >"$work/stubs.txt"
err=$(STUBS_TXT=$work/stubs.txt sh tools/starter.sh "$work/unmarked" --reading 2>&1 >/dev/null)
status=$?
[ $status -ne 0 ] && printf '%s\n' "$err" | grep "kit-hit-triangle" | grep -q "FindNearestHit, which has no statement"
check $? "a section that replaces a marked line where there is none stops the kit: $err"

sh tools/starter.sh "$work/solved" --solved >/dev/null
solved=$work/solved/rt-starter
build "$solved"
! grep -q "warning:" "$solved/build.log"
check $? "rt's bodies in the kit build with no warning: $(grep "warning:" "$solved/build.log" | head -3)"
out=$(kitmake "$solved" test 2>&1)
check $? "rt's bodies pass every check of the kit: $(printf '%s\n' "$out" | grep -v "^== " | tail -5)"
out=$(kitmake "$solved" grade 2>&1)
check $? "a solved kit passes make grade in the kit: $(printf '%s\n' "$out" | grep -v "^pass" | tail -3)"
flow=$solved/.github/workflows/classroom.yml
for scene in $(sed 's/ .*//' "$solved/grade/set/scenes.txt"); do
    grep -q "command: make grade SCENE=$scene\$" "$flow"
    check $? "the kit's GitHub Classroom workflow grades $scene"
done
grep -q "command: make test\$" "$flow" && grep -q "autograding-grading-reporter@v1" "$flow" &&
    grep -q "^  - push" "$flow"
check $? "the workflow runs on each push, runs the checks, and reports to GitHub Classroom"
sed -n 's/^ *command: //p' "$flow" | head -n 3 >"$work/commands"
while read -r command; do
    (cd "$solved" && MAKEFLAGS= CXXFLAGS=-O0 $command >/dev/null 2>&1)
    check $? "the workflow's \`$command\` passes in a solved kit"
done <"$work/commands"

# make reading: the reading edition is the solved kit's code (which the checks above built, ran
# and drew byte for byte), without the kit's grader, references and workflow
sh tools/starter.sh "$work/reading" --reading >/dev/null
diff -r -x README.md -x stubs.list -x grade -x references -x .github -x build -x 'build.log' \
    -x ray -x '*.png' "$work/solved/rt-starter" "$work/reading" >"$work/reading.diff"
check $? "the reading edition is the solved kit's code: $(head -5 "$work/reading.diff")"
[ ! -e "$work/reading/grade" ] && grep -q "reading edition" "$work/reading/README.md"
check $? "the reading edition has its own README and no grader"
missing=""
for name in $(grep -o '`[A-Z][A-Za-z]*`' "$work/reading/README.md" | tr -d '`' | sort -u); do
    grep -q "^[A-Za-z].*[ *]$name(" "$work/reading"/*.cpp "$work/reading"/*.h || missing="$missing $name"
done
[ -z "$missing" ]
check $? "every function the reading edition's README names is defined in it:$missing"

# Each classic bug written into a solved kit (tests/kit_bugs.txt) fails a check of its own step
# with that step's advice, and no check of an earlier step; and the grader names it on its scene.
all="get-ray normals sphere cramer plane nearest-hit shadow floor reflect depth phong refraction clamp"
grep -v '^#' tests/kit_bugs.txt >"$work/bugs"
allset=$work/allset
build/grade-set "$allset" --steps "$all" --tiny build/tiny
bugkit=$work/bugkit
cp -R "$solved" "$bugkit"
while read -r bug step file function script; do
    sed "/^[a-z].*[ *]$function(/,/^}/{
$script
}" "$solved/$file" >"$bugkit/$file"
    ! cmp -s "$solved/$file" "$bugkit/$file"
    check $? "the $bug bug is written into $file's $function (tests/kit_bugs.txt still fits the code)"
    kitmake "$bugkit" ray build/run_tests >"$work/bug.log" 2>&1
    check $? "a kit with the $bug bug builds: $(grep error "$work/bug.log" | head -2)"
    out=$(cd "$bugkit" && build/run_tests $all 2>&1)
    own=$(printf '%s\n' "$out" | awk -v s="$step" '/^== /{ sec = $2; next } sec == s && /^tests\// && !/ first: its checks fail/' | head -n 1)
    earlier=$(printf '%s\n' "$out" | awk -v s="$step" '/^== /{ if ($2 == s) done = 1; next } !done && /^tests\//' | head -n 1)
    [ -n "$own" ]
    check $? "the $bug bug fails a check of the $step step, with its advice: $(printf '%s\n' "$out" | grep -A2 "^== $step")"
    [ -z "$earlier" ]
    check $? "the $bug bug fails no check of a step before $step: $earlier"
    advice=$(sed -n "s/^$bug //p" "$allset/bugs.txt")
    for scene in $(awk -v b="$bug" '{ for (i = 2; i <= NF; i++) { split($i, n, "="); if (n[1] == b) print $1 } }' "$allset/scenes.txt"); do
        triangle="" # (a kit's ./ray draws triangles by Cramer's rule unless plane is its step)
        [ "$step" = plane ] && triangle="--triangle plane"
        line=$(build/grader "$allset" --scene "$scene" -- "$bugkit/ray" $triangle | head -n 1)
        printf '%s\n' "$line" | grep -qF "looks like $advice"
        check $? "the grader names the kit's $bug bug on $scene: $line"
    done
    cp "$solved/$file" "$bugkit/$file"
done <"$work/bugs"

(cd "$solved" && ./ray -o "$work/kit.png" >/dev/null 2>&1) && "$root/ray" --methods handout -o "$work/rt.png" >/dev/null 2>&1 &&
    "$root/ray" --compare "$work/kit.png" "$work/rt.png" >/dev/null
check $? "the solved kit draws rt's image under the handouts' methods, byte for byte"

sh tools/starter.sh "$work/wings" --solved --with-wings >/dev/null
wings=$work/wings/rt-starter
build "$wings"
! grep -q "warning:" "$wings/build.log" && (cd "$wings" && ./ray -o "$work/wings.png" >/dev/null 2>&1) &&
    "$root/ray" -o "$work/rt-default.png" >/dev/null 2>&1 &&
    "$root/ray" --compare "$work/wings.png" "$work/rt-default.png" >/dev/null
check $? "a kit with robust/ and fast/, solved, builds with no warning and draws rt's own image"
echo "$passed passed, $failed failed"
