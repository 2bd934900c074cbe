// tests/test_hard_cases.cpp -- every sphere, triangle and offset hard case (hard_cases.cpp) must
// pass with rt's default routines, in the double and in the float test program (cases that belong
// to one precision only run there). The REF and PH cases are in test_effects.cpp.
#include "hard_cases.h"
#include "test.h"

void TestHardCases() {
    std::vector<HardCaseResult> results;
    RunHardCases(IntersectSphere, IntersectTriangle, &results);
    for (const HardCaseResult &r : results)
        CHECK(r.passed, "hard case " + r.id + (r.passed ? "" : ": " + r.detail));
    CHECK(results.size() >= (sizeof(real) == 8 ? 21u : 15u),
          "the hard-case suite ran its rows (" + std::to_string(results.size()) + ")");
}
