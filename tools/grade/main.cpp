// tools/grade/main.cpp -- the grader's command line (`make grade` in rt and in the kit, the
// Gradescope bundle's run_autograder, a class's marks).
#include "grade.h"

#include <algorithm>
#include <atomic>
#include <climits>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <dirent.h>
#include <mutex>
#include <sys/stat.h>
#include <thread>
#include <unistd.h>

static const char kGraderUsage[] =
    "usage: grader SET [options] -- PROGRAM [ARGS...]   grade a tracer: PROGRAM ARGS SCENE -o OUT.png\n"
    "       grader SET [options] --images DIR           grade DIR/NAME.png (or .ppm), a scene each\n"
    "       grader SET [options] --class DIR --kit KIT  build and grade each submission folder in DIR\n"
    "       grader SET [options] --submission DIR --kit KIT   one submission (Gradescope)\n"
    "SET is a reference set (grade-set). Options:\n"
    "  --time S        seconds a scene may take, building too (default 10)\n"
    "  --scene NAME    grade one scene only\n"
    "  --max-bytes N   the largest file a tracer may write (default 64 MB)\n"
    "  --follow CMD    the command that prints a pixel's ray tree ({scene}: the scene's name)\n"
    "  --report FILE   write a page for the student (HTML)\n"
    "  --json FILE     write Gradescope's results.json\n"
    "  --out DIR       class: where marks.csv, the reports and the compiled files go\n"
    "  --jobs N        class: submissions built and graded at once (default: every core)\n"
    "  --objects DIR   a submission: where compiled files are kept, to share between runs\n"
    "  --cxx, --cxxflags, --libs   how submissions are compiled and linked\n";

struct Command {
    std::string set, images, classDir, submission, report, json, out = "build/grade/class";
    std::vector<std::string> program;
    GradeOptions options = {{10, 64L << 20, 4L << 30}, "", "./ray scenes/grade/{scene}.scene --methods handout --pixel"};
    BuildSettings build = {"", "c++", "-O2 -std=c++17 -ffp-contract=off -pthread", "-lpng -pthread", "", {120, 1L << 30, 0}};
    int jobs = 0;
};

static bool Parse(int argc, char **argv, Command *c) {
    if (argc < 2)
        return false;
    c->set = argv[1];
    for (int i = 2; i < argc; i++) {
        std::string a = argv[i];
        if (a == "--") {
            c->program.assign(argv + i + 1, argv + argc);
            return !c->program.empty();
        }
        if (i + 1 >= argc)
            return false;
        std::string v = argv[++i];
        if (a == "--time")
            c->options.limits.seconds = atof(v.c_str());
        else if (a == "--max-bytes")
            c->options.limits.outputBytes = atol(v.c_str());
        else if (a == "--scene")
            c->options.onlyScene = v;
        else if (a == "--follow")
            c->options.follow = v;
        else if (a == "--images")
            c->images = v;
        else if (a == "--class")
            c->classDir = v;
        else if (a == "--submission")
            c->submission = v;
        else if (a == "--kit")
            c->build.kit = v;
        else if (a == "--report")
            c->report = v;
        else if (a == "--json")
            c->json = v;
        else if (a == "--out")
            c->out = v;
        else if (a == "--jobs")
            c->jobs = atoi(v.c_str());
        else if (a == "--cxx")
            c->build.cxx = v;
        else if (a == "--cxxflags")
            c->build.cxxflags = v;
        else if (a == "--libs")
            c->build.libs = v;
        else if (a == "--objects")
            c->build.objects = v;
        else
            return false;
    }
    return !c->images.empty() || ((!c->classDir.empty() || !c->submission.empty()) && !c->build.kit.empty());
}

// *path made absolute (the compiler runs in another folder); it must exist.
static bool Absolute(std::string *path) {
    char resolved[PATH_MAX];
    if (!realpath(path->c_str(), resolved))
        return false;
    *path = resolved;
    return true;
}

static bool AllPass(const std::vector<SceneResult> &results) {
    for (const SceneResult &r : results)
        if (r.verdict != VERDICT_PASS)
            return false;
    return !results.empty();
}

// A submission that does not build fails every scene with the compiler's first error.
static std::vector<SceneResult> NotBuilt(const ReferenceSet *set, const GradeOptions *options,
                                         const std::string &error) {
    std::vector<SceneResult> results;
    for (const SetScene &s : set->scenes)
        if (options->onlyScene.empty() || options->onlyScene == s.name)
            results.push_back({s.name, VERDICT_NOT_BUILT, "does not build: " + error, 0, 0, {}, {}});
    return results;
}

// One submission: built (in a scratch folder of its own), then graded.
static std::vector<SceneResult> GradeSubmission(const ReferenceSet *set, const Command *c,
                                                const std::string &dir) {
    std::string work, error;
    if (!MakeScratch("rt-build-", &work, &error))
        return NotBuilt(set, &c->options, error);
    std::vector<SceneResult> results =
        BuildSubmission(&c->build, dir, work, &error)
            ? GradeProgram(set, {work + "/ray"}, &c->options)
            : NotBuilt(set, &c->options, error);
    RemoveTree(work);
    return results;
}

// The submission folders of a class: DIR's folders, by name.
static std::vector<std::string> Students(const std::string &dir) {
    std::vector<std::string> names;
    if (DIR *d = opendir(dir.c_str())) {
        while (struct dirent *e = readdir(d)) {
            struct stat info;
            if (e->d_name[0] != '.' && stat((dir + "/" + e->d_name).c_str(), &info) == 0 &&
                S_ISDIR(info.st_mode))
                names.push_back(e->d_name);
        }
        closedir(d);
    }
    std::sort(names.begin(), names.end());
    return names;
}

static void Write(const std::string &path, const std::string &text) {
    std::string error;
    if (!WriteTextFile(path, text, &error))
        fprintf(stderr, "grader: %s\n", error.c_str());
}

// A class: every submission built and graded, as many at once as there are cores; a report
// each (NAME.html, NAME.txt) and marks.csv in the out folder.
static int GradeClass(const ReferenceSet *set, Command *c) {
    std::vector<std::string> students = Students(c->classDir);
    mkdir(c->out.c_str(), 0777);
    c->build.objects = c->out + "/objects";
    mkdir(c->build.objects.c_str(), 0777);
    Absolute(&c->build.objects);
    int jobs = c->jobs > 0 ? c->jobs : std::max(1u, std::thread::hardware_concurrency());
    BuildKitObjects(&c->build, jobs);
    std::vector<std::vector<SceneResult>> results(students.size());
    std::atomic<size_t> next(0);
    std::mutex print;
    auto worker = [&]() {
        for (size_t k; (k = next++) < students.size();) {
            results[k] = GradeSubmission(set, c, c->classDir + "/" + students[k]);
            Write(c->out + "/" + students[k] + ".txt", TextReport(results[k]));
            Write(c->out + "/" + students[k] + ".html", HtmlReport(students[k], results[k], set));
            std::lock_guard<std::mutex> hold(print);
            std::string last = TextReport(results[k]);
            last.pop_back();
            printf("%s: %s\n", students[k].c_str(), last.substr(last.rfind('\n') + 1).c_str());
            fflush(stdout);
        }
    };
    std::vector<std::thread> threads;
    for (int k = 0; k < jobs; k++)
        threads.emplace_back(worker);
    for (std::thread &t : threads)
        t.join();
    std::string csv = CsvHeader(set);
    for (size_t k = 0; k < students.size(); k++)
        csv += CsvRow(students[k], results[k]);
    Write(c->out + "/marks.csv", csv);
    printf("%zu submissions: %s/marks.csv, and a report each (NAME.html, NAME.txt)\n", students.size(),
           c->out.c_str());
    return 0;
}

int main(int argc, char **argv) {
    signal(SIGPIPE, SIG_IGN);
    Command c;
    if (!Parse(argc, argv, &c)) {
        fputs(kGraderUsage, stderr);
        return 2;
    }
    ReferenceSet set;
    std::string error;
    if (!ReadReferenceSet(c.set, &set, &error)) {
        fprintf(stderr, "grader: %s\n", error.c_str());
        return 2;
    }
    if (!c.classDir.empty())
        return GradeClass(&set, &c);
    std::vector<SceneResult> results;
    if (!c.images.empty())
        results = GradeImages(&set, c.images, &c.options);
    else if (!c.submission.empty()) {
        std::string scratch;
        if (c.build.objects.empty() && MakeScratch("rt-objects-", &scratch, &error))
            c.build.objects = scratch;
        mkdir(c.build.objects.c_str(), 0777);
        Absolute(&c.build.objects);
        results = GradeSubmission(&set, &c, c.submission);
        if (!scratch.empty())
            RemoveTree(scratch);
    } else
        results = GradeProgram(&set, c.program, &c.options);
    std::string text = TextReport(results);
    fputs(text.c_str(), stdout);
    if (!c.report.empty())
        Write(c.report, HtmlReport("rt's grader", results, &set));
    if (!c.json.empty())
        Write(c.json, GradescopeJson(results, text));
    return AllPass(results) ? 0 : 1;
}
