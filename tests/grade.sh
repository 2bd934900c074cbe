#!/bin/sh
# The grader (tools/grade.sh) held to its purpose: each grading scene catches the tiny tracer
# with its bug (tests/grade/tiny.cpp --bug) and names that bug, and every other scene passes it;
# rt and the tiny tracer without a bug pass every scene. Ends with `N passed, M failed`.
set -u
passed=0 failed=0
check() { # check CONDITION-STATUS TEXT
    if [ "$1" -eq 0 ]; then passed=$((passed + 1)); else failed=$((failed + 1)) && echo "tests/grade.sh: FAILED $2"; fi
}
grade() { sh tools/grade.sh "$@" 2>&1; }

out=$(grade ./ray); check $? "rt itself passes every grading scene: $out"
out=$(grade build/tiny); check $? "the tiny tracer without a bug passes every scene: $out"
out=$(grade "./ray_float --methods handout"); check $? "a tracer in float passes every scene: $out"
for bug in normals acne beyond reflect far-root no-limit upside-down mirrored edges; do
    out=$(grade "build/tiny --bug $bug")
    check $((! $?)) "the tracer with the $bug bug fails the grade"
    for scene in scenes/grade/*.scene; do
        name=$(basename "$scene" .scene)
        line=$(printf '%s\n' "$out" | grep -E "^(pass|FAIL)  $name(:|$)")
        reveals=" $(sed -n 's/^# reveals: //p' "$scene") "
        if [ "${reveals#* $bug }" != "$reveals" ]; then
            case $line in
            "FAIL  $name:"*"looks like"*) named=$(printf '%s' "$line" | sed 's/.*looks like //; s/ (follow one: .*)$//') ;;
            *) named="" ;;
            esac
            expected=$(grade --advice "$bug")
            [ -n "$named" ] && [ "$named" = "$expected" ]
            check $? "$name.scene catches the $bug bug and names it: $line"
        else
            [ "$line" = "pass  $name" ]
            check $? "$name.scene passes the tracer with the $bug bug: $line"
        fi
    done
done

# A folder of images: rt's own pass; one replaced by an upside-down tracer's fails, named.
dir=build/grade/folder
rm -rf "$dir" && mkdir -p "$dir"
cp build/grade/reference/*.png "$dir/"
out=$(grade --images "$dir"); check $? "a folder of rt's images passes: $out"
build/tiny --bug upside-down scenes/grade/camera.scene -o "$dir/camera.png"
out=$(grade --images "$dir")
status=$?
case $out in *"FAIL  camera:"*"looks like $(grade --advice upside-down)"*) r=$status ;; *) r=0 ;; esac
check $((! r)) "a folder with an upside-down camera.png fails it, named: $out"

# A tracer that crashes (as one with no limit on its chain of rays does) fails every scene.
out=$(grade false)
status=$?
case $out in *"FAIL  acne: the tracer exited with status 1"*) r=$status ;; *) r=0 ;; esac
check $((! r)) "a tracer that exits with an error fails, and says so: $out"
echo "$passed passed, $failed failed"
