// tests/kit_main.cpp -- a starter kit's test program: `run_tests NAME...` runs the checks of
// the handouts' steps named (the functions listed in stubs.list; tests/test_handout.cpp) and
// ends with `N passed, M failed`. Each failure says what the step should give, what yours gave,
// and the most likely cause.
#include "test.h"

#include <cstdio>
#include <cstring>

static int passedChecks = 0, failedChecks = 0;

void TestCheck(bool ok, const char *file, int line, const std::string &why,
               const std::string &detail) {
    (void)detail;
    if (ok) {
        passedChecks++;
        return;
    }
    failedChecks++;
    printf("%s:%d: %s\n", file, line, why.c_str());
}

int main(int argc, char **argv) {
    for (int k = 1; k < argc; k++) {
        bool known = false;
        for (int g = 0; g < kHandoutGroupCount; g++)
            if (strcmp(argv[k], kHandoutGroups[g].name) == 0) {
                printf("== %s\n", argv[k]);
                kHandoutGroups[g].run();
                known = true;
            }
        if (!known) {
            fprintf(stderr, "run_tests: no checks for '%s'; the steps:", argv[k]);
            for (int g = 0; g < kHandoutGroupCount; g++)
                fprintf(stderr, " %s", kHandoutGroups[g].name);
            fprintf(stderr, "\n");
            return 2;
        }
    }
    printf("%d passed, %d failed\n", passedChecks, failedChecks);
    return failedChecks == 0 ? 0 : 1;
}
