// tools/grade/set_read.cpp -- a reference set (grade.h), read whole into memory before anything of
// a student's runs.
#include "grade.h"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <sstream>

bool ReadSmallFile(const std::string &path, size_t maxBytes, std::string *text, std::string *error) {
    FILE *file = fopen(path.c_str(), "rb");
    if (!file) {
        *error = path + ": " + strerror(errno);
        return false;
    }
    text->clear();
    char chunk[4096];
    for (size_t n; (n = fread(chunk, 1, sizeof chunk, file)) > 0 && text->size() <= maxBytes;)
        text->append(chunk, n);
    bool read = !ferror(file) && text->size() <= maxBytes;
    fclose(file);
    if (!read)
        *error = path + ": " + (text->size() > maxBytes ? "larger than a grading file can be" : strerror(errno));
    return read;
}

// The advice of each bug in bugs.txt: `NAME what it is and what to do`, a line each.
static bool ReadAdvice(const std::string &dir, std::vector<std::pair<std::string, std::string>> *advice,
                       std::string *error) {
    std::string text;
    if (!ReadSmallFile(dir + "/bugs.txt", 1 << 20, &text, error))
        return false;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) {
        size_t space = line.find(' ');
        if (space != std::string::npos)
            advice->push_back({line.substr(0, space), line.substr(space + 1)});
    }
    return true;
}

bool ReadReferenceSet(const std::string &dir, ReferenceSet *set, std::string *error) {
    std::vector<std::pair<std::string, std::string>> advice;
    std::string list;
    if (!ReadAdvice(dir, &advice, error) || !ReadSmallFile(dir + "/scenes.txt", 1 << 20, &list, error))
        return false;
    std::istringstream lines(list);
    for (std::string line; std::getline(lines, line);) {
        std::istringstream words(line);
        SetScene scene;
        if (!(words >> scene.name))
            continue;
        std::string base = dir + "/" + scene.name;
        if (!ReadSmallFile(base + ".scene", 1 << 20, &scene.text, error) ||
            !ReadImage((base + ".png").c_str(), &scene.reference, error) ||
            !ReadImage((base + ".shapes.png").c_str(), &scene.shapes, error))
            return false;
        for (std::string word; words >> word;) {
            std::vector<std::string> names; // the bug, then those that draw the scene alike
            for (size_t at = 0, end; at <= word.size(); at = end + 1) {
                end = std::min(word.find_first_of("=,", at), word.size());
                names.push_back(word.substr(at, end - at));
            }
            SetBug b = {names[0], "", {}, {}};
            for (size_t k = 0; k < names.size(); k++)
                for (const auto &a : advice)
                    if (a.first == names[k] && k == 0)
                        b.advice = a.second;
                    else if (a.first == names[k])
                        b.alike.push_back(a.second);
            if (!ReadImage((base + ".bug." + b.name + ".png").c_str(), &b.image, error))
                return false;
            scene.bugs.push_back(b);
        }
        set->scenes.push_back(scene);
    }
    if (set->scenes.empty()) {
        *error = dir + "/scenes.txt: no scenes";
        return false;
    }
    return true;
}
