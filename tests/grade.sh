#!/bin/sh
# The grader (tools/grade/, tools/grade.sh) held to its purpose. For the public scenes and for a
# varied seed (SEEDS, default "0 1"): every correct tracer passes every scene (rt in double and
# float, robust and handout methods, the tiny tracer with Cramer's rule or the plane test); the
# tiny tracer with each known bug (tests/grade/tiny.cpp --bug) fails each scene made for the bug,
# named, and on any other scene passes, or fails in words without naming another bug. Then each
# way a run can end gets its own true verdict, a tracer cannot change the references, paths with
# spaces work, two gradings run side by side, and the reports hold what they promise.
# Ends with `N passed, M failed`.
set -u
passed=0 failed=0
check() { # check STATUS TEXT: STATUS 0 passes
    if [ "$1" -eq 0 ]; then passed=$((passed + 1)); else failed=$((failed + 1)) && echo "tests/grade.sh: FAILED $2"; fi
}
has() { printf '%s\n' "$1" | grep -qF -- "$2"; } # has TEXT PART
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
steps="get-ray sphere cramer nearest-hit shadow floor reflect depth plane phong"
bugs="upside-down mirrored aspect far-root sphere-tmin edges inside-gamma inside-beta cramer-sign
      t-sign triangle-tmin plane-axis plane-order first-hit acne beyond nl-clamp l-length reflect
      no-limit depth-9 depth-11 phong-view phong-shadow phong-tint normals clamp"

# line OUTPUT SCENE: the grader's line for the scene
line() { printf '%s\n' "$1" | grep -E "^(pass|FAIL)  $2( |:|$)"; }

for seed in ${SEEDS:-0 1}; do
    set=$work/set-$seed
    build/grade-set "$set" --seed "$seed" --steps "$steps" --tiny build/tiny
    check $? "seed $seed: grade-set writes the set"
    scenes=$(sed 's/ .*//' "$set/scenes.txt")
    for tracer in "./ray" "./ray --methods handout" "./ray_float" "./ray_float --methods handout" \
        "build/tiny" "build/tiny --triangle plane"; do
        out=$(build/grader "$set" -- $tracer)
        check $? "seed $seed: $tracer passes every scene: $out"
    done
    for bug in $bugs; do
        out=$(build/grader "$set" -- build/tiny --bug "$bug")
        advice=$(sed -n "s/^$bug //p" "$set/bugs.txt")
        own=" $(awk -v b="$bug" '{ for (i = 2; i <= NF; i++) { split($i, n, "="); if (n[1] == b) print $1 } }' \
            "$set/scenes.txt" | tr '\n' ' ')"
        [ "$own" != " " ]
        check $? "seed $seed: some scene is made to show the $bug bug"
        for scene in $scenes; do
            l=$(line "$out" "$scene")
            case $own in
            *" $scene "*)
                has "$l" "looks like $advice"
                check $? "seed $seed: $scene.scene catches the $bug bug and names it: $l" ;;
            *)
                case $l in
                "pass  $scene" | "pass  $scene "*) r=0 ;;
                *"looks like"*) has "$l" "$advice" && r=0 || r=1 ;; # (named among bugs drawn alike)
                "FAIL  $scene: "*"unlike rt's: "*) r=0 ;;
                *) r=1 ;;
                esac
                check $r "seed $seed: $scene.scene passes the $bug bug, or fails it blaming no other bug: $l" ;;
            esac
        done
    done
done
set=$work/set-0 # (the public scenes, for what follows)
[ -d "$set" ] || build/grade-set "$set" --steps "$steps" --tiny build/tiny
[ "$(ls scenes/grade | sed 's/\.scene$//' | sort)" = "$(sed 's/ .*//' "$set/scenes.txt" | sort)" ]
check $? "scenes/grade holds the public scenes, one file each"
for scene in $(sed 's/ .*//' "$set/scenes.txt"); do
    cmp -s "$set/$scene.scene" "scenes/grade/$scene.scene"
    check $? "scenes/grade/$scene.scene is seed 0's scene"
done

# Tracers that end every way a run can end (each script is called as `SCRIPT SCENE -o OUT`).
ray=$(pwd)/ray
tracer() { # tracer NAME BODY: a script in $work
    printf '#!/bin/sh\n%s\n' "$2" >"$work/$1" && chmod +x "$work/$1"
}
tracer hang 'sleep 30'
tracer fork '(sleep 31 &); sleep 32'
tracer crash 'kill -SEGV $$'
tracer silent 'exit 0'
tracer exit3 "\"$ray\" \"\$1\" --methods handout -o \"\$3\" >/dev/null; exit 3"
tracer exit3none 'exit 3'
tracer garbage 'echo hello >"$3"'
tracer small "\"$ray\" \"\$1\" --methods handout --size 32 -o \"\$3\""
tracer link "ln -s \"$ray\" \"\$3\""
tracer big 'exec head -c 3000000 /dev/zero >"$3"'
tracer bigchild 'head -c 3000000 /dev/zero >"$3"'
grade1() { build/grader "$set" --scene acne --time 1 --max-bytes 1000000 -- "$@" 2>&1; }
start=$(date +%s)
out=$(grade1 "$work/hang")
check $((! $?)) "a tracer that hangs fails: $out"
has "$out" "FAIL  acne: timed out after 1"
check $? "a tracer that hangs is timed out: $out"
out=$(grade1 "$work/fork")
has "$out" "FAIL  acne: timed out after 1"
check $? "a tracer that forks and hangs is timed out: $out"
[ $(($(date +%s) - start)) -lt 20 ]
check $? "each was stopped at its time limit of 1 s, not when it would have ended (30 s on)"
sleep 1
! ps -eo args | grep -q "^sleep 3[12]$"
check $? "nothing a timed-out tracer started is left running"
# verdict TRACER EXPECTED WHAT: the tracer's line for acne holds EXPECTED
verdict() {
    out=$(grade1 "$work/$1")
    has "$out" "$2"
    check $? "$3: $out"
}
verdict crash "FAIL  acne: crashed (SIGSEGV)" "a tracer that crashes is said to crash, with its signal"
verdict silent "FAIL  acne: wrote no image (exit status 0)" "a tracer that writes nothing and exits 0 wrote no image"
verdict "no such tracer" "FAIL  acne: could not be run: No such file or directory" "a tracer that is not there does not run"
verdict exit3 "pass  acne (and it exited with status 3)" "an image written before exit status 3 is graded, the status noted"
verdict exit3none "FAIL  acne: exited with status 3 and wrote no image" "exit status 3 and no image"
verdict garbage "FAIL  acne: its image cannot be read" "an image that is not one is unreadable"
verdict small "FAIL  acne: the image is 32 x 32 pixels, the scene's 64 x 64" "an image of another size is said to be"
verdict link "is not a file" "an image that is a link to another file is not read"
verdict big "FAIL  acne: crashed (SIGXFSZ): it wrote a file larger than the limit" "a tracer that writes past the limit is stopped"
verdict bigchild "FAIL  acne: exited with status 153 (a program it ran ended with SIGXFSZ) and" \
    "a script whose command writes past the limit is told what its status means"

# make grade as a teacher runs it: references no tracer can reach, paths with spaces, two at once
grade() { CXX="${CXX:-g++}" KIT_CXXFLAGS="" PNG_LIBS="" sh tools/grade.sh 2>&1; }
tracer tamper "printf 'P6\\n64 64\\n255\\n' >\"\$3\" && head -c 12288 /dev/zero >>\"\$3\"
for f in \"\${TMPDIR:-/tmp}\"/rt-set-*/*.png \"$(pwd)\"/build/grade/*/*.png; do cp \"\$3\" \"\$f\" 2>/dev/null; done"
out=$(TRACER=$work/tamper grade)
status=$?
[ $status -ne 0 ] && ! printf '%s\n' "$out" | grep -q "^pass"
check $? "a tracer that writes its image over every reference it can find passes nothing: $out"
mkdir -p "$work/my tracer" && cp ray "$work/my tracer/ray"
out=$(TRACER="$work/my tracer/ray" grade)
check $? "a tracer in a folder whose name has a space is graded: $out"
(TRACER=./ray grade >"$work/side1" 2>&1; echo $? >"$work/side1.status") &
(TRACER=./ray_float grade >"$work/side2" 2>&1; echo $? >"$work/side2.status") &
wait
[ "$(cat "$work/side1.status")$(cat "$work/side2.status")" = 00 ]
check $? "two gradings side by side both pass: $(cat "$work/side1" "$work/side2" | grep -v "^pass")"

# A folder of images, and the reports
mkdir -p "$work/images"
for scene in $(sed 's/ .*//' "$set/scenes.txt"); do cp "$set/$scene.png" "$work/images/"; done
out=$(IMAGES=$work/images grade)
check $? "a folder of rt's images passes: $out"
rm "$work/images/camera.png"
out=$(IMAGES=$work/images grade)
has "$out" "FAIL  camera: no image camera.png (nor .ppm)"
check $? "a folder without camera.png says so: $out"
out=$(REPORT=$work/report.html JSON=$work/results.json TRACER="build/tiny --bug far-root" grade)
grep -q '<img src="data:image/png;base64,' "$work/report.html" && grep -q "far_root: differs" "$work/report.html"
check $? "the report shows a failing scene's images and its verdict"
n=$(printf '%s\n' "$out" | sed -n 's/^[0-9]* of \([0-9]*\) scenes pass$/\1/p')
for field in '"tests": \[' '"name": "far_root"' '"score": 0, "max_score": 1' '"output": ' '"visibility": "visible"'; do
    grep -q "$field" "$work/results.json"
    check $? "results.json has Gradescope's $field"
done
[ "$(grep -c '"max_score": 1' "$work/results.json")" -eq "$n" ]
check $? "results.json has a test a scene"
echo "$passed passed, $failed failed"
