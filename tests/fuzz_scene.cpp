// tests/fuzz_scene.cpp -- the libFuzzer target (`make fuzz`): scene files and probe lines.
#include "exercise.h"

#include <cstdio>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    std::string why;
    if (!ExerciseSceneText(std::string((const char *)data, size), &why)) {
        fprintf(stderr, "fuzz: %s\n", why.c_str());
        __builtin_trap();
    }
    return 0;
}
