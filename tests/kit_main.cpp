// tests/kit_main.cpp -- a starter kit's test program: `run_tests STEP...` runs the checks of the
// handouts' steps named (the steps of stubs.list; tests/test_handout.cpp), in the handouts'
// order, and ends with `N passed, M failed`. Each failure says what the step should give, what
// yours gave, and the most likely cause; where the check goes through an earlier step whose own
// checks fail, it says to fix that step first instead.
#include "test.h"

#include <cstdio>
#include <cstring>
#include <string>

// The run's tally; while `quiet`, failures are only counted (a step's health, found before its
// checks are shown); `blame`, when set, is the earlier step to fix first.
static int passedChecks = 0, failedChecks = 0;
static bool quiet = false;
static std::string blame;

void TestCheck(bool ok, const char *file, int line, const std::string &why,
               const std::string &detail) {
    (void)detail;
    ok ? passedChecks++ : failedChecks++;
    if (!ok && !quiet)
        printf("%s:%d: %s\n", file, line, why.c_str());
}

void TestAdvice(bool ok, const char *file, int line, const std::string &should,
                const std::string &got, const std::string &cause) {
    std::string why = should + "; " + got;
    if (!blame.empty())
        why += ": fix " + blame + " first: its checks fail, and this check goes through it";
    else if (!cause.empty())
        why += ": " + cause;
    TestCheck(ok, file, line, why, "");
}

static bool Listed(int argc, char **argv, const char *name) {
    for (int k = 1; k < argc; k++)
        if (strcmp(argv[k], name) == 0)
            return true;
    return false;
}

// Whether the step's checks all pass, run quietly.
static bool Passes(const HandoutGroup *g) {
    int before = failedChecks, passedBefore = passedChecks;
    quiet = true;
    g->run();
    quiet = false;
    bool passes = failedChecks == before;
    failedChecks = before, passedChecks = passedBefore;
    return passes;
}

// The first of the steps g goes through whose checks fail ("" if none).
static std::string FailingNeed(const HandoutGroup *g) {
    std::string needs = std::string(" ") + g->needs + " ";
    for (int k = 0; k < kHandoutGroupCount && &kHandoutGroups[k] != g; k++)
        if (needs.find(std::string(" ") + kHandoutGroups[k].name + " ") != std::string::npos &&
            !Passes(&kHandoutGroups[k]))
            return kHandoutGroups[k].name;
    return "";
}

int main(int argc, char **argv) {
    for (int k = 1; k < argc; k++) {
        bool known = false;
        for (int g = 0; g < kHandoutGroupCount; g++)
            known = known || strcmp(argv[k], kHandoutGroups[g].name) == 0;
        if (!known) {
            fprintf(stderr, "run_tests: no checks for '%s'; the steps:", argv[k]);
            for (int g = 0; g < kHandoutGroupCount; g++)
                fprintf(stderr, " %s", kHandoutGroups[g].name);
            fprintf(stderr, "\n");
            return 2;
        }
    }
    for (int g = 0; g < kHandoutGroupCount; g++) { // (in the handouts' order)
        const HandoutGroup *group = &kHandoutGroups[g];
        if (!Listed(argc, argv, group->name))
            continue;
        blame = FailingNeed(group);
        printf("== %s\n", group->name);
        group->run();
        blame.clear();
    }
    printf("%d passed, %d failed\n", passedChecks, failedChecks);
    return failedChecks == 0 ? 0 : 1;
}
