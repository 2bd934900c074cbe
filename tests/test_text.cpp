// test_text.cpp -- reading text (text.cpp): numbers as strtod (strtof in float) reads them, whole
// numbers with leading zeros, lines up to their limit and at every line ending, and the hint for
// a slip of the keyboard.
#include "../app/app.h"
#include "test.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>

// The number the C library reads from t: strtod's, or in float strtof's (rounded once).
static real LibraryNumber(const std::string &t) {
    if (sizeof(real) == sizeof(float))
        return (real)strtof(t.c_str(), nullptr);
    return (real)strtod(t.c_str(), nullptr);
}

// Numbers are read as strtod (strtof) reads them (ParseReal takes a faster road to the same
// number): 20,000 decimal numbers of every form a scene file may hold, signs, no digits before
// or after the point, long mantissas, exponents out to 1e-450 and 1e450, give the same bits, or
// are refused exactly where the library's answer is infinite or a nonzero number read as 0.
static void TestNumbersAsStrtod() {
    uint64_t state = 12345;
    auto next = [&state](int n) { // a number from 0 to n - 1 (a linear congruential generator)
        state = state * 6364136223846793005ull + 1442695040888963407ull;
        return (int)((state >> 33) % (uint64_t)n);
    };
    int differ = 0;
    std::string first;
    for (int k = 0; k < 20000; k++) {
        std::string t = next(3) == 0 ? "" : next(2) ? "-" : "+";
        int whole = next(4) == 0 ? 0 : 1 + next(20), part = next(3) == 0 ? 0 : 1 + next(25);
        for (int i = 0; i < whole; i++)
            t += (char)('0' + (next(3) == 0 ? 0 : next(10)));
        if (part > 0 || whole == 0 || next(4) == 0)
            t += '.';
        for (int i = 0; i < part || (whole == 0 && i == 0); i++)
            t += (char)('0' + next(10));
        if (next(2))
            t += (next(2) ? "e" : "E") +
                 std::string(next(3) == 0 ? "-"
                             : next(2)    ? "+"
                                          : "") +
                 std::to_string(next(4) == 0 ? next(451) : next(40));
        real r = LibraryNumber(t), v = 0;
        bool nonzero = t.find_first_of("123456789") < t.find_first_of("eE");
        bool expected = std::isfinite(r) && !(r == 0 && nonzero);
        std::string error;
        bool read = ParseReal(t, &v, &error);
        if (read != expected || (read && memcmp(&v, &r, sizeof v) != 0)) { // (-0 is not 0)
            if (differ++ == 0)
                first = t;
        }
    }
    CHECK(differ == 0, "20,000 decimal numbers read as strtod (strtof) reads them (" +
                           std::to_string(differ) + " differ; the first: '" + first + "')");
}

// A number is rounded once, to the build's own type. 1.00000005960464478 is 1 + 2^-24 and about
// 4.6e-18 more: just past the midpoint of the floats 1 and 1 + 2^-23, so as a float it is the
// latter, though the double nearest to it is the midpoint itself, which would round (to even)
// to 1.
static void TestRoundedOnce() {
    real v = 0;
    std::string error;
    bool read = ParseReal("1.00000005960464478", &v, &error);
    real expected = sizeof(real) == sizeof(float) ? real(1) + real(0x1p-23) : real(1 + 0x1p-24);
    CHECK(read && v == expected,
          "1.00000005960464478 is 1 + 2^-23 in float, 1 + 2^-24 in double (rounded once)");
}

// Whole numbers (--size, --spp, `size`, `depth`): leading zeros add nothing, however many, and
// too many digits is out of range, never an overflow.
static void TestWholeNumbers() {
    int v = 0;
    std::string error;
    CHECK(ParseWholeNumber("0000000000064", 1, 16384, &v, &error) && v == 64,
          "'0000000000064' is 64");
    CHECK(ParseWholeNumber("+00000000004", 1, 65536, &v, &error) && v == 4, "'+00000000004' is 4");
    CHECK(ParseWholeNumber("-000000000000", 0, 5, &v, &error) && v == 0, "'-000000000000' is 0");
    CHECK(!ParseWholeNumber("99999999999999999999999", 1, 16384, &v, &error) &&
              error.find("must be between 1 and 16384") != std::string::npos,
          "23 nines: must be between 1 and 16384");
    CHECK(!ParseWholeNumber("-4294967297", -5, 5, &v, &error) &&
              !ParseWholeNumber("4294967301", -5, 5, &v, &error),
          "-(2^32 + 1) and 2^32 + 5 are out of range, not wrapped into it");
}

// A line holds at most kMaxLineLength bytes, its line ending and comment not counted: one of
// exactly that many is read whole, byte for byte (past the reader's own buffer of 256), and one
// byte more is too long.
static void TestLineLimit() {
    for (size_t extra : {0, 1}) {
        std::string text, line;
        for (size_t k = 0; k < kMaxLineLength + extra; k++)
            text += (char)('a' + k % 26);
        std::string whole = text + "\r\nnext\n", error;
        FILE *file = fmemopen((void *)whole.data(), whole.size(), "r");
        CHECK(file != nullptr, "fmemopen makes a file of a string");
        if (!file)
            return;
        LineStatus status = ReadTextLine(file, 1, &line, &error);
        bool same = line == text;
        bool next = ReadTextLine(file, 2, &line, &error) == LINE_READ && line == "next";
        fclose(file);
        CHECK(extra == 0 ? status == LINE_READ && same && next : status == LINE_TOO_LONG && next,
              std::to_string(kMaxLineLength + extra) + " bytes and CR LF: " +
                  (extra == 0 ? "read whole" : "too long") + ", and the next line read after it");
    }
}

// NearWord names the known word a slip or two away, the nearest of several, and nothing for a
// word further away, a word it knows, or a word of one or two letters.
static void TestNearWord() {
    static const char *const kTwo[] = {"spheres", "sphere", nullptr};
    CHECK(NearWord("spherr", kTwo) == 1,
          "NearWord('spherr'): 'sphere', one slip away, not 'spheres', two slips and first");
    static const char *const kWords[] = {"size", "sphere", "spp", "view", "triangle", nullptr};
    const struct {
        const char *word;
        int near;
    } cases[] = {{"sise", 0},     {"spher", 1}, {"spehre", 1}, {"sphre", 1},
                 {"spe", 2},      {"vie", 3},   {"sixe", 0},   {"tirangle", 4},
                 {"trinagel", 4}, {"sppp", 2},  {"size", -1},  {"mast", -1},
                 {"sx", -1},      {"", -1},     {"spear", -1}, {"triangles", 4}};
    for (const auto &c : cases)
        CHECK(NearWord(c.word, kWords) == c.near,
              std::string("NearWord('") + c.word +
                  "'): " + (c.near < 0 ? std::string("none") : kWords[c.near]));
}

void TestText() {
    TestNumbersAsStrtod();
    TestRoundedOnce();
    TestWholeNumbers();
    TestLineLimit();
    TestNearWord();
}
