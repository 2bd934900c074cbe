# bench/stats.sh: the numbers make bench quotes (sourced by bench.sh and peers.sh, which set
# $out, their scratch folder).

# spread FILE: "median (min-max)" of the numbers in FILE, one a line
spread() { sort -g "$1" | awk '{ v[NR] = $1 } END { m = (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2; printf "%.1f (%.1f-%.1f)", m, v[1], v[NR] }'; }
median() { sort -g "$1" | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }

# ratio A B: the median of the ratios A_k / B_k of runs taken in turn (each pair saw the same load
# on the machine), with their quartiles; "within noise" where the quartiles hold 1.
ratio() {
    paste "$1" "$2" | awk '{ print $1 / $2 }' | sort -g | awk '{ v[NR] = $1 } END {
        m = (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2
        q1 = v[int((NR + 3) / 4)]; q3 = v[int((3 * NR + 3) / 4)]
        printf "%.2f (quartiles %.2f-%.2f)", m, q1, q3
        if (q1 <= 1 && 1 <= q3) printf ", within noise" }'
}

# timed NAME COMMAND...: one whole-process wall time in ms (rtbench: fork to exit), appended to
# $out/NAME; the command's --stats render time, if it prints one, to $out/NAME.render
timed() {
    name=$1
    shift
    build/double/rtbench time "$@" 2>"$out/stats" >>"$out/$name"
    sed -n 's/^time: render \([0-9.]*\) s.*/\1/p' "$out/stats" | awk '{ print $1 * 1000 }' >>"$out/$name.render"
    sed -n 's/^rays: .*total=\([0-9]*\)$/\1/p' "$out/stats" >"$out/$name.rays"
}

make_row() { # NAME LABEL: a table row of the whole-process and render times
    mrays=$(awk -v r="$(cat "$out/$1.rays")" -v t="$(median "$out/$1.render")" 'BEGIN { printf "%.2f", r / (t / 1000) / 1e6 }')
    printf '| %s | %s | %s | %s |\n' "$2" "$(spread "$out/$1")" "$(spread "$out/$1.render")" "$mrays"
}

# median2 FILE: the median to two decimals
median2() { printf '%.2f' "$(median "$1")"; }

# quartiles FILE: "q1-q3" of the numbers in FILE, one a line
quartiles() { sort -g "$1" | awk '{ v[NR] = $1 } END { printf "%.2f-%.2f", v[int((NR + 3) / 4)], v[int((3 * NR + 3) / 4)] }'; }
