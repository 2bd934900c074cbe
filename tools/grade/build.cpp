// tools/grade/build.cpp -- a submission built from its own sources: the kit's files as the student
// changed them (a file the submission lacks is the kit's), compiled by the grader's own command
// with a time limit, so that what is graded is what the student wrote, never a program handed in
// ready-made. The files every student left as the kit gave them are compiled once for the class:
// a compiled file is kept under a key made of its text, every header's text and the flags.
#include "grade.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <cstdio>
#include <dirent.h>
#include <map>
#include <mutex>
#include <sys/stat.h>
#include <thread>

// The folders of a kit whose sources make its program (robust/ and fast/ when a teacher kept them).
static const char *const kFolders[] = {"", "app/", "robust/", "fast/"};

static bool EndsWith(const std::string &s, const char *end) {
    size_t n = strlen(end);
    return s.size() >= n && s.compare(s.size() - n, n, end) == 0;
}

// The sources and headers of a kit or submission at root: relative path -> text. Only regular
// files of a source's size are read (a link or a huge file is not the student's code).
static void ReadSources(const std::string &root, std::map<std::string, std::string> *files) {
    for (const char *folder : kFolders) {
        DIR *d = opendir((root + "/" + folder).c_str());
        if (!d)
            continue;
        while (struct dirent *e = readdir(d)) {
            std::string rel = std::string(folder) + e->d_name, text, error;
            struct stat info;
            if ((EndsWith(rel, ".cpp") || EndsWith(rel, ".h")) &&
                lstat((root + "/" + rel).c_str(), &info) == 0 && S_ISREG(info.st_mode) &&
                ReadSmallFile(root + "/" + rel, 1 << 20, &text, &error))
                (*files)[rel] = text;
        }
        closedir(d);
    }
}

// Where a submission's kit is: its folder, or the one folder in it that holds ray.h (a
// repository downloaded as a folder of its own).
static std::string KitRoot(const std::string &dir) {
    struct stat info;
    if (stat((dir + "/ray.h").c_str(), &info) == 0)
        return dir;
    std::string only;
    int folders = 0;
    if (DIR *d = opendir(dir.c_str())) {
        while (struct dirent *e = readdir(d))
            if (e->d_name[0] != '.' && stat((dir + "/" + e->d_name + "/ray.h").c_str(), &info) == 0)
                only = dir + "/" + e->d_name, folders++;
        closedir(d);
    }
    return folders == 1 ? only : dir;
}

// FNV-1a, 64 bits, from two starting points: a 128-bit key in hex.
static std::string Key(const std::string &text) {
    uint64_t a = 0xcbf29ce484222325ULL, b = 0x84222325cbf29ce4ULL;
    for (unsigned char c : text) {
        a = (a ^ c) * 0x100000001b3ULL;
        b = (b ^ c) * 0x100000001b3ULL;
    }
    char hex[40];
    snprintf(hex, sizeof hex, "%016llx%016llx", (unsigned long long)a, (unsigned long long)b);
    return hex;
}

// Every header's path and text, as one string: a change to any header changes every key.
static std::string Headers(const std::map<std::string, std::string> &files) {
    std::string all;
    for (const auto &f : files)
        if (EndsWith(f.first, ".h"))
            all += f.first + '\0' + f.second + '\0';
    return all;
}

// The first line of the compiler's (or the linker's) output that says what is wrong: an
// `error:`, or an undefined reference; else its last line.
static std::string FirstError(const std::string &output) {
    size_t at = std::string::npos;
    for (const char *mark : {"error:", "undefined reference", "Undefined symbols"})
        at = std::min(at, output.find(mark));
    if (at == std::string::npos)
        at = output.empty() ? 0 : output.size() - 1;
    size_t start = output.rfind('\n', at), end = output.find('\n', at);
    start = start == std::string::npos ? 0 : start + 1;
    return output.substr(start, end == std::string::npos ? std::string::npos : end - start);
}

// Runs `sh -c command` in dir under the build's limits. False with *error.
static bool Shell(const BuildSettings *settings, const std::string &command, const std::string &dir,
                  std::string *error) {
    RunResult run;
    RunLimited({"/bin/sh", "-c", command}, dir, &settings->limits, &run);
    if (run.end == RUN_EXITED && run.status == 0)
        return true;
    *error = run.end == RUN_TIMED_OUT    ? "the compiler ran out of time"
             : run.end == RUN_NOT_STARTED ? "/bin/sh could not be run: " + run.why
                                          : FirstError(run.output);
    return false;
}

static std::string Quote(const std::string &s) {
    std::string out = "'";
    for (char c : s)
        out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

// The compiled file of source `rel` in the tree at src, from the shared folder if it is there.
static bool Compile(const BuildSettings *settings, const std::string &src, const std::string &rel,
                    const std::string &text, const std::string &headers, std::string *object,
                    std::string *error) {
    std::string flags = settings->cxx + " " + settings->cxxflags;
    *object = settings->objects + "/" + Key(flags + '\0' + rel + '\0' + text + '\0' + headers) + ".o";
    struct stat info;
    if (stat(object->c_str(), &info) == 0)
        return true;
    std::string temporary = *object + "." + Key(src) + ".tmp";
    return Shell(settings,
                 settings->cxx + " " + settings->cxxflags + " -I. -c " + Quote(rel) + " -o " +
                     Quote(temporary) + " && mv " + Quote(temporary) + " " + Quote(*object),
                 src, error);
}

// Writes the tree's files under src (its folders made first). False with *error.
static bool WriteTree(const std::map<std::string, std::string> &files, const std::string &src,
                      std::string *error) {
    for (const char *folder : kFolders)
        mkdir((src + "/" + folder).c_str(), 0777);
    for (const auto &f : files)
        if (!WriteTextFile(src + "/" + f.first, f.second, error))
            return false;
    return true;
}

bool BuildSubmission(const BuildSettings *settings, const std::string &dir, const std::string &work,
                     std::string *error) {
    std::map<std::string, std::string> files;
    ReadSources(settings->kit, &files);
    ReadSources(KitRoot(dir), &files); // (the student's files over the kit's)
    std::string src = work + "/src", headers = Headers(files), objects;
    mkdir(work.c_str(), 0777);
    mkdir(src.c_str(), 0777);
    if (!WriteTree(files, src, error))
        return false;
    for (const auto &f : files) {
        std::string object;
        if (!EndsWith(f.first, ".cpp"))
            continue;
        if (!Compile(settings, src, f.first, f.second, headers, &object, error)) {
            *error = f.first + ": " + *error;
            return false;
        }
        objects += " " + Quote(object);
    }
    return Shell(settings,
                 settings->cxx + " " + settings->cxxflags + " -o " + Quote(work + "/ray") + objects +
                     " " + settings->libs,
                 src, error);
}

void BuildKitObjects(const BuildSettings *settings, int jobs) {
    std::map<std::string, std::string> files;
    ReadSources(settings->kit, &files);
    std::string headers = Headers(files), work, error;
    if (!MakeScratch("rt-kit-", &work, &error) || !WriteTree(files, work, &error))
        return; // (each submission then compiles the kit's files itself)
    std::vector<std::string> sources;
    for (const auto &f : files)
        if (EndsWith(f.first, ".cpp"))
            sources.push_back(f.first);
    std::mutex lock;
    size_t next = 0;
    auto worker = [&]() {
        for (;;) {
            std::string rel, object, why;
            {
                std::lock_guard<std::mutex> hold(lock);
                if (next == sources.size())
                    return;
                rel = sources[next++];
            }
            Compile(settings, work, rel, files.at(rel), headers, &object, &why);
        }
    };
    std::vector<std::thread> threads;
    for (int k = 0; k < jobs; k++)
        threads.emplace_back(worker);
    for (std::thread &t : threads)
        t.join();
    RemoveTree(work);
}
