// tests/test_corpus.cpp -- replays every input the fuzzer kept (tests/corpus/) through the same
// readers: each must read or fail with file and line, render finite colours, and not crash.
#include "exercise.h"
#include "test.h"

#include <dirent.h>
#include <fstream>
#include <sstream>

void TestCorpus() {
    DIR *dir = opendir("tests/corpus");
    CHECK(dir != nullptr, "tests/corpus exists");
    if (!dir)
        return;
    int count = 0, failed = 0;
    std::string firstFailure;
    while (dirent *entry = readdir(dir)) {
        if (entry->d_name[0] == '.')
            continue;
        std::ifstream in(std::string("tests/corpus/") + entry->d_name, std::ios::binary);
        std::stringstream text;
        text << in.rdbuf();
        std::string why;
        count++;
        if (!ExerciseSceneText(text.str(), &why)) {
            failed++;
            if (firstFailure.empty())
                firstFailure = std::string(entry->d_name) + ": " + why;
        }
    }
    closedir(dir);
    CHECK(count > 0 && failed == 0, "fuzz corpus: " + std::to_string(count) +
                                        " inputs replay calmly" +
                                        (failed ? " (first failure: " + firstFailure + ")" : ""));
}
