// tests/hard_cases_suite.h -- what the hard-case files share (hard_cases.cpp,
// hard_cases_offset.cpp): the routines under test, the results, a deterministic sweep generator.
#ifndef RT_HARD_CASES_SUITE_H
#define RT_HARD_CASES_SUITE_H

#include "hard_cases.h"

#include <cstdint>

const bool kDouble = sizeof(real) == sizeof(double);

struct Suite {
    SphereRoutine sphere;
    TriangleRoutine triangle;
    std::vector<HardCaseResult> *results;
};

// Deterministic uniform numbers in [0, 1) for the sweeps (a 64-bit LCG).
struct SweepRng {
    uint64_t state;
    double Next() {
        state = state * 6364136223846793005ULL + 1442695040888963407ULL;
        return (double)(state >> 11) * (1.0 / 9007199254740992.0);
    }
};

inline void Report(Suite *s, const char *id, bool passed, const std::string &detail) {
    s->results->push_back({id, passed, detail});
}

// The self-intersection (OFF) cases (hard_cases_offset.cpp).
void OffsetRows(Suite *s);

#endif
