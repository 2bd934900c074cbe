// app/text.cpp -- reading text input: lines, tokens and numbers, for scene files and probes alike.
//
// Input is read a line at a time and never held whole, so a file of any size costs memory only
// for what it describes. A line ends at LF, CR LF or CR, as a text editor ends it, a comment's
// line too. A line is bounded (kMaxLineLength; a comment, from `#` to the line's end, is dropped
// as it is read and may hold anything else), a NUL byte elsewhere marks a file that is not text,
// and a UTF-8 byte-order mark (what Windows Notepad writes) at the start is skipped.
#include "app.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstdint>
#include <cstdio>
#include <cstdlib>

// Whether the `#` at line[hash] is part of a number as old Windows programs printed NaN and
// infinity (1.#QNAN, 1.#SNAN, -1.#IND, 1.#INF), not a comment: a digit or a point before it, and
// Q, S or I after it.
static bool WindowsSpecial(char before, char after) {
    return (std::isdigit((unsigned char)before) || before == '.') &&
           (after == 'Q' || after == 'S' || after == 'I');
}

size_t CommentStart(const std::string &line) {
    for (size_t k = line.find('#'); k != std::string::npos; k = line.find('#', k + 1))
        if (k == 0 || k + 1 == line.size() || !WindowsSpecial(line[k - 1], line[k + 1]))
            return k;
    return line.size();
}

// Whether byte c, just read, ends a line: LF, or CR, with the LF after it if there is one
// (Windows' CR LF; a CR alone ends a line of a classic Mac OS file).
static bool EndsLine(FILE *file, int c) {
    if (c == '\r') {
        int next = getc_unlocked(file);
        if (next != '\n' && next != EOF)
            ungetc(next, file);
    }
    return c == '\n' || c == '\r';
}

LineStatus ReadTextLine(FILE *file, int lineNumber, std::string *line, std::string *error) {
    line->clear();
    int c;
    bool tooLong = false, comment = false;
    // (Bytes are gathered a bufferful at a time, and read with getc_unlocked: the file is this
    // thread's alone, and a lock and an append for every byte would cost more than the reading.)
    char kept[256];                 // (any size would do: this one holds a mesh's usual line whole)
    size_t waiting = 0, length = 0; // bytes in `kept`; bytes of the line so far
    char last = 0;                  // the byte kept last
    while ((c = getc_unlocked(file)) != EOF && !EndsLine(file, c)) {
        if (c == '#' && !comment) { // a comment, unless a Windows NaN (CommentStart)
            int next = getc_unlocked(file);
            comment = !WindowsSpecial(last, (char)next);
            if (next != EOF)
                ungetc(next, file);
        }
        if (comment) // a comment is dropped as it is read: any length will do
            continue;
        if (c == 0) {
            bool bom = lineNumber == 1 && length >= 2 && waiting >= 2 &&
                       ((kept[0] == '\xFF' && kept[1] == '\xFE') ||
                        (kept[0] == '\xFE' && kept[1] == '\xFF'));
            *error = bom ? "UTF-16 text (the file begins with its byte-order mark): rt reads "
                           "ASCII or UTF-8; save the file as UTF-8"
                         : "a NUL byte: this is not a text file (or it is UTF-16, which has one "
                           "in every other byte: save it as UTF-8)";
            return LINE_BAD;
        }
        last = (char)c;
        tooLong = tooLong || length == kMaxLineLength; // then read on, keeping nothing
        if (tooLong)
            continue;
        if (waiting == sizeof kept)
            line->append(kept, waiting), waiting = 0;
        kept[waiting++] = (char)c, length++;
    }
    line->append(kept, waiting);
    if (ferror(file)) {
        *error = "read error";
        return LINE_BAD;
    }
    if (c == EOF && line->empty() && !tooLong)
        return LINE_END;
    if (lineNumber == 1 && line->compare(0, 3, "\xEF\xBB\xBF") == 0)
        line->erase(0, 3);
    if (tooLong) {
        *error = "line longer than " + std::to_string(kMaxLineLength) + " characters";
        return LINE_TOO_LONG;
    }
    return LINE_READ;
}

// Splits a line into tokens at spaces and tabs, up to a comment's `#`.
void Tokenize(const std::string &line, std::vector<std::string> *tokens) {
    tokens->clear();
    size_t k = 0, end = CommentStart(line);
    while (k < end) {
        while (k < end && (line[k] == ' ' || line[k] == '\t'))
            k++;
        size_t start = k;
        while (k < end && line[k] != ' ' && line[k] != '\t')
            k++;
        if (k > start)
            tokens->push_back(line.substr(start, k - start));
    }
}

// How many bytes from s[i] make one UTF-8 character (Unicode 15, table 3-7: no overlong form, no
// surrogate, nothing past U+10FFFF), and its code point; 0 if they do not make one.
static int Utf8Character(const std::string &s, size_t i, uint32_t *point) {
    unsigned char lead = (unsigned char)s[i];
    int n = lead < 0x80                    ? 1
            : lead >= 0xc2 && lead <= 0xdf ? 2
            : lead >= 0xe0 && lead <= 0xef ? 3
            : lead >= 0xf0 && lead <= 0xf4 ? 4
                                           : 0;
    if (n == 0 || i + n > s.size())
        return 0;
    uint32_t p = n == 1 ? lead : lead & (0x7f >> n);
    for (int k = 1; k < n; k++) {
        unsigned char c = (unsigned char)s[i + k];
        if ((c & 0xc0) != 0x80)
            return 0;
        p = p << 6 | (c & 0x3f);
    }
    const uint32_t least[5] = {0, 0, 0x80, 0x800, 0x10000};
    if (p < least[n] || (p >= 0xd800 && p <= 0xdfff) || p > 0x10ffff)
        return 0;
    *point = p;
    return n;
}

// Whether code point p is a control character (C0, DEL and C1), a Unicode line or paragraph
// separator, or a bidirectional embedding, override or isolate: what a terminal acts on rather
// than shows (the last would turn the rest of a message around on the screen).
static bool IsControl(uint32_t p) {
    return p < 0x20 || (p >= 0x7f && p <= 0x9f) || p == 0x2028 || p == 0x2029 ||
           (p >= 0x202a && p <= 0x202e) || (p >= 0x2066 && p <= 0x2069);
}

// The optimal string alignment distance (Damerau's four slips: a letter added, dropped or
// changed, two neighbours swapped), by the usual table of prefixes, one row at a time.
static size_t Slips(const std::string &a, const std::string &b) {
    std::vector<size_t> before(b.size() + 1), row(b.size() + 1), next(b.size() + 1);
    for (size_t j = 0; j <= b.size(); j++)
        row[j] = j;
    for (size_t i = 1; i <= a.size(); i++) {
        next[0] = i;
        for (size_t j = 1; j <= b.size(); j++) {
            size_t change = row[j - 1] + (a[i - 1] != b[j - 1]);
            next[j] = std::min({row[j] + 1, next[j - 1] + 1, change});
            if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
                next[j] = std::min(next[j], before[j - 2] + 1);
        }
        before.swap(row), row.swap(next);
    }
    return row[b.size()];
}

int NearWord(const std::string &word, const char *const *known) {
    int nearest = -1;
    size_t fewest = 3;   // (more than any word may be away)
    if (word.size() < 3) // one slip could make a word of one or two letters almost anything
        return -1;
    for (int i = 0; known[i]; i++) {
        std::string k = known[i];
        if (word == k)
            return -1;                       // a word rt knows is no slip
        size_t most = k.size() >= 6 ? 2 : 1; // (lengths further apart: more slips than that)
        if (word.size() > k.size() + most || k.size() > word.size() + most)
            continue;
        size_t slips = Slips(word, k);
        if (slips <= most && slips < fewest) // the nearest; of equals, the first
            nearest = i, fewest = slips;
    }
    return nearest;
}

// A token as it may be shown in a message: at most 40 code points, each printable one as written
// ("sphère" stays "sphère"), and each byte of a control character (IsControl) or of bytes that
// are not UTF-8 as '?', which counts as one. (Counted in code points, so a cut never splits the
// bytes of one; it may part a letter from an accent written as a code point of its own.)
std::string Shown(const std::string &token) {
    const int kMost = 40;
    std::string s;
    size_t i = 0;
    for (int shown = 0; i < token.size() && shown < kMost; shown++) {
        uint32_t p = 0;
        int n = Utf8Character(token, i, &p);
        if (n > 0 && !IsControl(p))
            s.append(token, i, n), i += n;
        else
            s += '?', i++;
    }
    return "'" + s + (i < token.size() ? "...'" : "'");
}

std::string PrintableLine(const std::string &text) {
    std::string line;
    for (size_t i = 0; i < text.size();) {
        uint32_t p = 0;
        int n = Utf8Character(text, i, &p);
        if (n > 0 && !IsControl(p)) {
            line.append(text, i, n), i += n;
        } else if (text[i] == '\n') {
            line += "\\n", i++;
        } else { // a control character, a byte at a time, or a byte that is not UTF-8
            for (int k = 0; k < std::max(n, 1); k++, i++) {
                char escape[8];
                snprintf(escape, sizeof escape, "\\x%02x", (unsigned char)text[i]);
                line += escape;
            }
        }
    }
    return line;
}

bool IsPrintableText(const std::string &text) { return PrintableLine(text) == text; }

bool IsUtf8(const std::string &text) {
    uint32_t p;
    for (size_t i = 0, n; i < text.size(); i += n)
        if ((n = (size_t)Utf8Character(text, i, &p)) == 0)
            return false;
    return true;
}

// Decimal digits with an optional sign, point and exponent: -2, +0.5, 1e-3, .5, 5.
bool LooksDecimal(const std::string &t) {
    size_t k = 0, digits = 0;
    if (k < t.size() && (t[k] == '+' || t[k] == '-'))
        k++;
    for (; k < t.size() && isdigit((unsigned char)t[k]); k++)
        digits++;
    if (k < t.size() && t[k] == '.')
        for (k++; k < t.size() && isdigit((unsigned char)t[k]); k++)
            digits++;
    if (digits == 0)
        return false;
    if (k < t.size() && (t[k] == 'e' || t[k] == 'E')) {
        k++;
        if (k < t.size() && (t[k] == '+' || t[k] == '-'))
            k++;
        size_t start = k;
        for (; k < t.size() && isdigit((unsigned char)t[k]); k++) {
        }
        if (k == start)
            return false;
    }
    return k == t.size();
}

// Whether a decimal number has a digit other than 0 before its exponent.
static bool NonzeroDigits(const std::string &t) {
    for (char c : t) {
        if (c == 'e' || c == 'E')
            return false;
        if (c >= '1' && c <= '9')
            return true;
    }
    return false;
}

// The T nearest to a decimal token (LooksDecimal), rounded once: as strtod (or strtof) gives it,
// by std::from_chars (which takes no '+', and is faster than strtod: a large mesh is mostly
// numbers). Where from_chars does not read the whole token, or finds it out of range, strtod or
// strtof reads it, and tells too large (infinity) from too small (0). A float is read as a float:
// read as the nearest double and then rounded again, a decimal just past the midpoint of two
// floats may land on it and round to the other one (1.00000005960464478 would be 1, not the
// float after it). (Where the library does not declare from_chars for floating types
// (__cpp_lib_to_chars), as libc++ may not, strtod or strtof alone: the same number, more slowly.)
template <typename T> static T Nearest(const std::string &token) {
#if defined(__cpp_lib_to_chars)
    T v;
    const char *first = token.data() + (token[0] == '+'), *last = token.data() + token.size();
    std::from_chars_result read = std::from_chars(first, last, v);
    if (read.ec == std::errc() && read.ptr == last)
        return v;
#endif
    if constexpr (sizeof(T) == sizeof(float))
        return strtof(token.c_str(), nullptr);
    else
        return strtod(token.c_str(), nullptr);
}

bool ParseReal(const std::string &token, real *value, std::string *error) {
    if (!LooksDecimal(token)) {
        bool windows = token.find(".#") != std::string::npos;
        *error = "not a decimal number: " + Shown(token) +
                 (windows ? " (old Windows programs printed NaN and infinity so: the program "
                            "that wrote it had no number to write)"
                          : "");
        return false;
    }
    real v = Nearest<real>(token);
    if (!std::isfinite(v)) {
        *error = "number out of range: " + Shown(token);
        return false;
    }
    // A number too small to be anything but 0 (1e-400; in float 1e-50) is refused as a number
    // too large is: read as 0, a radius of 1e-50 would be refused as "not > 0", and a direction
    // as "zero", for a number that is neither. (A nonzero digit before the exponent: not 0.)
    if (v == 0 && NonzeroDigits(token)) {
        *error = "number out of range (too small, it would be 0): " + Shown(token);
        return false;
    }
    *value = v;
    return true;
}

bool TooSmallForNumber(const std::string &token) {
    return LooksDecimal(token) && Nearest<real>(token) == 0 && NonzeroDigits(token);
}

bool IsWholeNumber(const std::string &token) {
    size_t k = !token.empty() && (token[0] == '+' || token[0] == '-') ? 1 : 0;
    return k < token.size() && token.find_first_not_of("0123456789", k) == std::string::npos;
}

bool ParseWholeNumber(const std::string &token, int lo, int hi, int *value, std::string *error) {
    if (!IsWholeNumber(token)) {
        *error = "not a whole number: " + Shown(token);
        return false;
    }
    // Leading zeros add nothing (0000064 is 64); past them, more than 10 digits is beyond any
    // int, and strtoll could not hold 20
    size_t first = token.find_first_not_of("+-0");
    size_t digits = first == std::string::npos ? 0 : token.size() - first;
    long long v = digits <= 10 ? strtoll(token.c_str(), nullptr, 10) : lo - 1LL;
    if (v < lo || v > hi) {
        *error = "must be between " + std::to_string(lo) + " and " + std::to_string(hi) + ", not " +
                 Shown(token);
        return false;
    }
    *value = (int)v;
    return true;
}
