#!/bin/sh
# bench/class.sh [N] -- what grading a class costs: N submissions (default 50) made from a solved
# kit, every one after the first with one classic bug of tests/kit_bugs.txt written in (in turn,
# so about one in 28 is correct), graded as a teacher does, `make grade CLASS=DIR` with the
# kit's flags (-O2), on every core. Writes build/bench/class.md: the wall time of the whole
# class (the kit's own files compiled once, then each submission built and graded), per
# submission, and how the verdicts came out. Run after `make`; not part of make bench (a
# few minutes on two cores).
set -eu
n=${1:-50}
dir=build/bench
mkdir -p "$dir"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cores=$(getconf _NPROCESSORS_ONLN 2>/dev/null || echo 1)

make -s ray build/tiny build/grader build/grade-set build/references/reference.png >/dev/null
make -s starter >/dev/null 2>&1
sh tools/starter.sh "$work/solved" --solved >/dev/null 2>&1
grep -v '^#' tests/kit_bugs.txt >"$work/bugs"
bugs=$(wc -l <"$work/bugs")
class=$work/class
mkdir -p "$class"
k=0
while [ "$k" -lt "$n" ]; do
    student=$(printf 'student%03d' "$k")
    cp -R "$work/solved/rt-starter" "$class/$student"
    rm -rf "$class/$student/build" "$class/$student/grade" "$class/$student/references"
    b=$((k % (bugs + 1)))
    if [ "$b" -gt 0 ]; then
        sed -n "${b}p" "$work/bugs" >"$work/bug"
        read -r bug step file function script <"$work/bug"
        sed "/^[a-z].*[ *]$function(/,/^}/{
$script
}" "$work/solved/rt-starter/$file" >"$class/$student/$file"
    fi
    k=$((k + 1))
done

start=$(date +%s)
make -s grade CLASS="$class" OUT="$work/marks" >"$work/out.txt" 2>&1 || true
end=$(date +%s)
seconds=$((end - start))
scenes=$(head -n 1 "$work/marks/marks.csv" | tr ',' '\n' | grep -vc '^student$\|^passed$\|^total$')
allpass=$(awk -F, -v s="$scenes" 'NR > 1 && $(NF - 1) == s' "$work/marks/marks.csv" | wc -l)
{
    echo "# Grading a class, $(date -u +%Y-%m-%d), $cores cores"
    echo
    echo "$n submissions (a solved kit, each after the first with one of the $bugs bugs of"
    echo "tests/kit_bugs.txt in turn), graded by \`make grade CLASS=DIR\` on $scenes scenes:"
    echo
    echo "| | |"
    echo "|---|---|"
    echo "| whole class, wall time | $seconds s |"
    echo "| a submission | $(awk -v s="$seconds" -v n="$n" 'BEGIN { printf "%.1f s", s / n }') |"
    echo "| passing every scene | $allpass of $n |"
    echo
    echo "The last lines of the grader:"
    echo
    echo '```'
    tail -n 3 "$work/out.txt"
    echo '```'
} >"$dir/class.md"
cat "$dir/class.md"
