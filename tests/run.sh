#!/bin/sh
# Runs the test programs given, all at once (each is one process, and the machine's cores share
# them; an argument may carry the program's own arguments, "build/sanitize/run_tests --claim DIR"),
# then shows each one's output in the order given and ends with the sum of their counts as the
# last line: `N passed, M failed`. Exits non-zero if any test failed or a program crashed.
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
echo "running $# test programs at once"
i=0
for program in "$@"; do
    i=$((i + 1))
    ($program >"$dir/$i.out" 2>"$dir/$i.err"; echo $? >"$dir/$i.status") &
done
wait

passed=0
failed=0
i=0
for program in "$@"; do
    i=$((i + 1))
    echo "== $program"
    status=$(cat "$dir/$i.status")
    sed '$d' "$dir/$i.out"
    cat "$dir/$i.err"
    last=$(tail -n 1 "$dir/$i.out")
    echo "   $program: $last"
    p=$(printf '%s\n' "$last" | sed -n 's/^\([0-9]*\) passed, \([0-9]*\) failed$/\1/p')
    f=$(printf '%s\n' "$last" | sed -n 's/^\([0-9]*\) passed, \([0-9]*\) failed$/\2/p')
    if [ -z "$p" ] || [ "$status" -ne 0 -a "$f" = 0 ]; then
        echo "   $program did not finish (exit status $status)"
        f=$((${f:-0} + 1))
        p=${p:-0}
    fi
    passed=$((passed + p))
    failed=$((failed + f))
done
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
