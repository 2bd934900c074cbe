# tools/starter/regions.awk -- one source file as a starter kit has it (tools/starter.sh). The
# first file read is stubs.txt (its `@@ NAME` sections, their comment lines kept as `hints`
# says: N| always, F| for formula and steps, S| for steps; P| code only with plane=1, a kit whose
# students write the plane test, not Cramer's rule); the second, the source. A region
# `// starter: begin NAME` ... `// starter: end` becomes NAME's section where NAME is one of
# `stubs` (the names of stubs.list, each between spaces) or begins with kit-; elsewhere its lines
# stay, without the two marker lines. solved=1 keeps every student region's lines (rt's bodies
# in place of the stubs), for the test that they pass the kit's checks; wings=1 keeps the kit-
# regions, for a kit with robust/ and fast/.
FNR == NR {
    if ($0 ~ /^@@ /) {
        name = substr($0, 4)
        known[name] = 1
        text[name] = ""
    } else if (name != "") {
        line = $0
        mark = substr(line, 1, 2)
        if (mark == "N|" || mark == "F|" || mark == "S|" || mark == "P|") {
            if ((mark == "F|" && hints == "none") || (mark == "S|" && hints != "steps") ||
                (mark == "P|" && !plane))
                next
            line = substr(line, 3)
        }
        text[name] = text[name] line "\n"
    }
    next
}
/^[ \t]*\/\/ starter: begin / {
    region = $0
    sub(/^.*\/\/ starter: begin /, "", region)
    sub(/[ \t].*$/, "", region)
    if (!(region in known)) {
        print FILENAME ":" FNR ": no section `@@ " region "` in stubs.txt" >"/dev/stderr"
        failed = 1
        exit 1
    }
    replace = region ~ /^kit-/ ? !wings : !solved && index(stubs, " " region " ") > 0
    if (replace)
        printf "%s", text[region]
    inside = 1
    next
}
/^[ \t]*\/\/ starter: end/ { inside = 0; next }
inside && replace { next }
{ print }
