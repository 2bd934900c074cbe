// tests/hard_cases.h -- the catalogue of numerical hard cases (docs/robustness.md) as code.
//
// Each row of the catalogue is one case with its exact expected result. The suite takes the
// sphere and triangle routines to test as function pointers, so `make test` runs it on the
// defaults (every applicable row must pass) and `make bench` counts what the handout's Cramer
// form and the textbook sphere quadratic pass.
#ifndef RT_HARD_CASES_H
#define RT_HARD_CASES_H

#include "../ray.h"

typedef bool (*SphereRoutine)(const Sphere *, const Ray *, real, real, RayHit *);
typedef bool (*TriangleRoutine)(const Triangle *, const Ray *, real, real, RayHit *);

struct HardCaseResult {
    std::string id; // the catalogue's id, e.g. "SPH-1"
    bool passed;
    std::string detail; // what was found, for a failure message
};

// Runs every row that applies to this build's precision (some rows are double-only, some
// float-only) with the given routines, appending one result per row.
void RunHardCases(SphereRoutine sphere, TriangleRoutine triangle,
                  std::vector<HardCaseResult> *results);

#endif
