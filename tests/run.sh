#!/bin/sh
# Runs each test program given, shows its output, and ends with the sum of their counts as the
# last line: `N passed, M failed`. Exits non-zero if any test failed or a program crashed.
passed=0
failed=0
for program in "$@"; do
    echo "== $program"
    out=$("$program")
    status=$?
    printf '%s\n' "$out" | sed '$d'
    last=$(printf '%s\n' "$out" | tail -n 1)
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
