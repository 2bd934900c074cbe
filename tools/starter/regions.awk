# tools/starter/regions.awk -- one source file as a starter kit has it (tools/starter.sh). The
# first file read is stubs.txt, the second the source. Each section of stubs.txt, `@@ NAME KIND
# F...`, says what it replaces in the source, by the name of a top-level definition:
#   body F      F's body (the lines after the one that opens it, up to its `}` at column 0)
#               becomes the section's lines;
#   whole F...  each definition F (a function, or a constant `... F = ...;`), with the comment
#               lines just above it, becomes the section's lines (none: it goes, and the blank
#               line after it);
#   mark F      the statements in F whose first line ends in a mark `// robust/: ...` or
#               `// fast/: ...` become the section's lines (where the first was);
#   unused F... F gets `[[maybe_unused]]`: a helper that a stub may leave unused.
# A step's section (NAME one of `stubs`, the names of stubs.list, each between spaces) applies
# unless solved=1 (rt's bodies kept, for the test that they pass the kit's checks); a kit-
# section unless wings=1 (a kit with robust/ and fast/); an `unused` one unless solved=1. A
# marked statement that no section names is left out unless wings=1: the mark says what a reader
# of rt may skip there. A section's lines that begin N|, F|, S| or P| are kept as `hints` says:
# N| always, F| for formula and steps, S| for steps; P| code only with plane=1 (a kit whose students write the
# plane test, not Cramer's rule). Every definition of a name that a section gives is written to
# the file `found` (with " mark" for each marked statement in a function), for tools/starter.sh
# to check that each is defined once. Marked statements and signatures hold no `//` in strings.
BEGIN { width = 100 } # (.clang-format's ColumnLimit, for the signatures `unused` lengthens)

FNR == NR {
    if ($0 ~ /^@@ /) {
        name = $2
        kind[name] = $3
        text[name] = ""
        if ($3 !~ /^(body|whole|mark|unused)$/ || NF < 4)
            Fail(FILENAME ":" FNR ": `@@ NAME body|whole|mark|unused NAME...`, not `" $0 "`")
        for (i = 4; i <= NF; i++)
            if ($3 == "unused")
                helper[$i] = name
            else if ($i in owner)
                Fail(FILENAME ":" FNR ": " $i " is named by " owner[$i] " too")
            else
                owner[$i] = name
    } else if (name != "") {
        line = $0
        hint = substr(line, 1, 2)
        if (hint == "N|" || hint == "F|" || hint == "S|" || hint == "P|") {
            if ((hint == "F|" && hints == "none") || (hint == "S|" && hints != "steps") ||
                (hint == "P|" && !plane))
                next
            line = substr(line, 3)
        }
        text[name] = text[name] line "\n"
    }
    next
}

function Fail(message) {
    print "tools/starter/regions.awk: " message >"/dev/stderr"
    failed = 1
    exit 2
}

function Applies(s) {
    if (kind[s] == "unused")
        return !solved
    if (s ~ /^kit-/)
        return !wings
    return !solved && index(stubs, " " s " ") > 0
}

function Code(line) { # (the line without its comment)
    sub(/[ \t]*\/\/.*$/, "", line)
    return line
}

function Flush() {
    printf "%s", pending
    pending = ""
}

# The name a column-0 line begins to define, or "": a function (isFunction) or a constant.
function DefinedName(line,    code, eq, name) {
    code = Code(line)
    sub(/[{].*$/, "", code)
    eq = index(code, "=")
    isFunction = match(code, /[A-Za-z_][A-Za-z0-9_]*[(]/) && (eq == 0 || RSTART < eq)
    if (isFunction)
        return substr(code, RSTART, RLENGTH - 1)
    if (eq == 0 || !match(substr(code, 1, eq - 1), /[A-Za-z_][A-Za-z0-9_]*(\[\])?[ \t]*$/))
        return ""
    name = substr(code, RSTART, RLENGTH)
    sub(/[^A-Za-z0-9_].*$/, "", name)
    return name
}

function SignatureEnds(line,    code) {
    code = Code(line)
    return isFunction ? code ~ /[{};][ \t]*$/ : code ~ /;[ \t]*$/
}

# The signature with `[[maybe_unused]] ` before it, its parameters filled in greedily to the
# column limit and the lines after the first aligned past its `(`, as clang-format lays it out.
function MaybeUnused(sig,    n, part, i, one, piece, open, indent, out, row, next_) {
    n = split(sig, part, "\n")
    one = "[[maybe_unused]] " part[1]
    for (i = 2; i < n; i++) {
        piece = part[i]
        sub(/^[ \t]+/, "", piece)
        one = one " " piece
    }
    if (length(one) <= width)
        return one "\n"
    open = index(one, "(")
    indent = sprintf("%" open "s", "")
    n = split(substr(one, open + 1), part, ", ")
    row = substr(one, 1, open) part[1]
    out = ""
    for (i = 2; i <= n; i++) {
        next_ = row ", " part[i] (i < n ? "," : "")
        if (length(next_) <= width)
            row = row ", " part[i]
        else {
            out = out row ",\n"
            row = indent part[i]
        }
    }
    return out row "\n"
}

# A definition's signature is complete: print it, replaced or not, and go on to its body.
function EndSignature(last,    s, oneLine) {
    state = ""
    if (isFunction && Code(last) ~ /;[ \t]*$/) { # (a declaration)
        Flush()
        printf "%s", sig
        return
    }
    if (found != "" && ((sigName in owner) || (sigName in helper)))
        print sigName >>found
    s = (sigName in owner) ? owner[sigName] : ""
    oneLine = !isFunction || Code(last) ~ /[}][ \t]*$/
    if (sigName in helper && Applies(helper[sigName]))
        sig = MaybeUnused(sig)
    if (s != "" && kind[s] == "whole" && Applies(s)) {
        DropComments()
        gone = text[s] == "" # (then the blank line after it goes too)
        if (!gone) {
            Flush()
            printf "%s", text[s]
        }
        afterWhole = oneLine && gone
        if (!oneLine) {
            state = "skip"
            closing = ""
        }
        return
    }
    Flush()
    if (oneLine && s != "" && kind[s] == "body" && Applies(s)) { # (a body on its signature's line)
        sub(/[ \t]*[{].*$/, " {", sig)
        printf "%s\n%s}\n", sig, text[s]
        return
    }
    printf "%s", sig
    if (oneLine)
        return
    if (s != "" && kind[s] == "body" && Applies(s)) {
        printf "%s", text[s]
        state = "skip"
        closing = "}"
        return
    }
    inBody = 1
    current = sigName
}

function DropComments(    n, part, i, kept) { # (the comment above a definition that goes)
    n = split(pending, part, "\n")
    kept = ""
    for (i = 1; i < n; i++)
        if (part[i] == "")
            kept = kept "\n"
    pending = kept
}

# Whether the statement being left out goes on past this line of code: until its braces close
# and a line ends in `;` or `}`.
function GoesOn(code,    open, shut) {
    open = gsub(/[{]/, "{", code)
    shut = gsub(/[}]/, "}", code)
    depth += open - shut
    return !(depth <= 0 && code ~ /[;}][ \t]*$/)
}

# A line with a mark: the statement it begins is left out, or replaced by its function's
# `mark` section; an #include is one line.
function Marked(line,    s, code) {
    if (found != "")
        print current " mark" >>found
    Flush()
    if (wings) {
        print line
        return
    }
    s = (current in owner) ? owner[current] : ""
    if (s != "" && kind[s] == "mark" && Applies(s) && marks[current]++ == 0)
        printf "%s", text[s]
    code = Code(line)
    if (code ~ /^[ \t]*#/)
        return
    depth = 0
    orElse = code ~ /^[ \t]*if[ \t(]/
    state = GoesOn(code) ? "statement" : orElse ? "else?" : ""
}

FNR != NR && state == "sig" {
    sig = sig $0 "\n"
    if (SignatureEnds($0))
        EndSignature($0)
    next
}
FNR != NR && state == "skip" {
    if ($0 ~ /^}/) {
        state = ""
        if (closing != "")
            print closing
        else
            afterWhole = gone
    }
    next
}
FNR != NR && state == "statement" {
    if (!GoesOn(Code($0)))
        state = orElse ? "else?" : ""
    next
}
FNR != NR && state == "else?" {
    state = ""
    if ($0 ~ /^[ \t]*else([ \t{]|$)/) {
        orElse = $0 ~ /^[ \t]*else[ \t]+if[ \t(]/
        depth = 0
        state = GoesOn(Code($0)) ? "statement" : orElse ? "else?" : ""
        next
    }
}
FNR != NR {
    if (afterWhole) {
        afterWhole = 0
        if ($0 == "")
            next
    }
    if (!inBody && ($0 == "" || $0 ~ /^\/\//)) {
        pending = pending $0 "\n"
        next
    }
    if ($0 ~ /^[A-Za-z_]/ && (sigName = DefinedName($0)) != "" &&
        (isFunction || (sigName in owner))) {
        sig = $0 "\n"
        if (SignatureEnds($0))
            EndSignature($0)
        else
            state = "sig"
        next
    }
    if ($0 ~ /\/\/ (robust|fast)\/: /) {
        Marked($0)
        next
    }
    if ($0 ~ /^}/) {
        inBody = 0
        current = ""
    }
    Flush()
    print
}
END {
    if (failed)
        exit 2
    if (state == "sig" || state == "skip")
        Fail(FILENAME ": ends inside " sigName)
    if (state == "statement")
        Fail(FILENAME ": ends inside a marked statement")
    sub(/\n+$/, "\n", pending) # (a file does not end in blank lines, even where a definition went)
    if (pending == "\n")
        pending = ""
    Flush()
}
