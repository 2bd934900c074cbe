// tools/grade/grade.h -- the grader: holds a student's ray tracer to rt's images on small scenes,
// each made so that some classic bugs show, and names a bug where the image is that bug's.
//
// A reference set is a folder written by grade-set (set.cpp, in rt only): the scenes, rt's image
// of each, a map of which shape each pixel shows, the images a tracer with each of the scene's
// known bugs draws, and what to say of each bug. The grader reads the whole set into memory
// before it runs anything of a student's, and never reads it again: nothing a student's program
// writes can change the references. The student's program runs once a scene in a scratch folder
// of its own, with a time limit and a cap on what it may write (run.cpp); only its image is read
// back, and judged (judge.cpp). report.cpp writes what a student and a teacher read; build.cpp
// builds a class's submissions, each from its own sources.
#pragma once
#include "app/app.h"

#include <string>
#include <vector>

// ---- scenes.cpp: the grading scenes (rt only) ----------------------------------------------

struct GradingScene {
    std::string name, text; // the text opens with `# reveals: BUG BUG ...`
};

// The grading scenes for a seed: 0 the public ones (scenes/grade/), any other a variation of
// each (positions, sizes, colours, lights) in which its bugs still show.
std::vector<GradingScene> MakeGradingScenes(unsigned long seed);

// ---- set_read.cpp: a reference set in memory --------------------------------------------------

struct SetBug {
    std::string name, advice; // advice: what the bug is and what to do, in the handouts' words
    Image image;              // the scene as a tracer with this bug draws it
    std::vector<std::string> alike; // the advice of other known bugs that draw this scene alike
};

struct SetScene {
    std::string name, text; // the scene file's name (NAME.scene) and its text
    Image reference;        // rt's image under the handouts' methods
    Image shapes;           // each pixel's shape: the line of the scene file that makes it, in
                            // red (low byte) and green (high byte); 0 for the background
    std::vector<SetBug> bugs;
};

struct ReferenceSet {
    std::vector<SetScene> scenes;
    std::string scenesDir; // where a reader finds the scene files, for the --pixel command
};

// Reads the set in dir (scenes.txt names the scenes, in order, each with the bugs it is made to
// show, `BUG=OTHER,OTHER` where other bugs draw the scene alike; bugs.txt says what each bug is). False with *error naming the file that is missing or unreadable.
bool ReadReferenceSet(const std::string &dir, ReferenceSet *set, std::string *error);

// The text of a file, at most maxBytes of it; false with *error ("PATH: why").
bool ReadSmallFile(const std::string &path, size_t maxBytes, std::string *text, std::string *error);

// ---- run.cpp: running a program of a student's --------------------------------------------

struct Limits {
    double seconds;    // wall-clock time before the program's whole process group is killed
    long outputBytes;  // the largest file it may write (RLIMIT_FSIZE)
    long memoryBytes;  // its address space (RLIMIT_AS); 0 leaves it unlimited
};

enum RunEnd {
    RUN_EXITED,      // status: its exit status
    RUN_SIGNALED,    // status: the signal that ended it
    RUN_TIMED_OUT,   // killed after Limits::seconds
    RUN_NOT_STARTED  // why: the program does not exist or cannot be run
};

struct RunResult {
    RunEnd end;
    int status;
    std::string why;    // RUN_NOT_STARTED: strerror's words
    std::string output; // the last lines it wrote to standard output and error
    double seconds;
};

// Runs argv in dir (its working folder) with stdin from /dev/null and its output kept in
// memory (the last part, under the same cap), in a process group of its own that is killed
// whole when the program ends or its time is up. argv[0] is looked for in PATH unless it holds
// a `/`. The environment is the grader's.
void RunLimited(const std::vector<std::string> &argv, const std::string &dir, const Limits *limits,
                RunResult *result);

// The signal's name (SIGSEGV), or "signal N".
std::string SignalName(int signal);

// A fresh private folder under $TMPDIR (or /tmp), and removing a folder with all it holds (links
// are removed, never followed). False with *error.
bool MakeScratch(const char *prefix, std::string *dir, std::string *error);
void RemoveTree(const std::string &dir);

// ---- judge.cpp: one scene's verdict ------------------------------------------------------

enum Verdict {
    VERDICT_PASS,
    VERDICT_DIFFERS,    // the image differs from rt's in more pixels than allowed
    VERDICT_CRASHED,    // ended by a signal
    VERDICT_TIMED_OUT,  // killed at the time limit
    VERDICT_EXITED,     // a non-zero exit status and no image
    VERDICT_NO_IMAGE,   // exit status 0 and no image
    VERDICT_UNREADABLE, // an image that is neither PNG nor PPM, or cut short
    VERDICT_WRONG_SIZE, // an image of another size than the scene's
    VERDICT_NOT_RUN,    // the program does not exist or cannot be run
    VERDICT_NOT_BUILT   // (class mode) the submission does not build
};

// The verdict's word in marks.csv and results.json.
const char *VerdictWord(Verdict verdict);

struct SceneResult {
    std::string scene;
    Verdict verdict;
    std::string text;     // what the student reads: one line, what went wrong and what to do
    long differing;       // pixels over the tolerance (VERDICT_DIFFERS and VERDICT_PASS)
    long allowed;         // the most that may differ and still pass
    Image image, heatmap; // the student's image and where it differs (for the report)
};

// A channel off by at most this counts as equal (a float tracer, another rounding); a scene
// passes when at most one pixel in kPassRatio differs more.
const int kTolerance = 4;
const long kPassRatio = 200;

// Judges one scene: how the program's run ended (nullptr: images graded without a run), and
// its image (nullptr: none was written; *imageError says why it cannot be read, if one was).
// `follow` is the command that prints the ray tree of a pixel of this scene, up to `--pixel`.
void Judge(const SetScene *scene, const RunResult *run, const Image *image,
           const std::string &imageError, const std::string &follow, SceneResult *result);

// ---- grade.cpp: a program or a folder of images over the whole set --------------------------

struct GradeOptions {
    Limits limits;
    std::string onlyScene; // grade this scene alone ("" every scene)
    std::string follow;    // the command that prints a pixel's ray tree, up to `--pixel`, with
                           // {scene} for the scene's name
};

// Grades the command (a program and its first arguments; each scene's path and `-o NAME.png`
// are added) on every scene of the set.
std::vector<SceneResult> GradeProgram(const ReferenceSet *set, const std::vector<std::string> &command,
                                      const GradeOptions *options);

// Grades the images DIR/NAME.png (or NAME.ppm) of a tracer run by hand.
std::vector<SceneResult> GradeImages(const ReferenceSet *set, const std::string &dir,
                                     const GradeOptions *options);

// ---- report.cpp: what the grades are written as ------------------------------------------

// One line a scene (`pass  NAME` or `FAIL  NAME: ...`), then `K of N scenes pass`.
std::string TextReport(const std::vector<SceneResult> &results);

// A page a student can read: each scene's verdict, and beside a failing one rt's image, the
// student's and where they differ. Images are inside the page (data: URIs), so it is one file.
std::string HtmlReport(const std::string &title, const std::vector<SceneResult> &results,
                       const ReferenceSet *set);

// Gradescope's results.json: one test a scene, scored 1 when it passes.
std::string GradescopeJson(const std::vector<SceneResult> &results, const std::string &output);

// marks.csv: a header row, then one row a student (its scenes' verdicts, passed, total).
std::string CsvHeader(const ReferenceSet *set);
std::string CsvRow(const std::string &student, const std::vector<SceneResult> &results);

// Writes text to path, through a temporary file renamed into place. False with *error.
bool WriteTextFile(const std::string &path, const std::string &text, std::string *error);

// ---- build.cpp: a submission built from its own sources (class mode, Gradescope) ----------

struct BuildSettings {
    std::string kit;      // the kit the students were given: the files a submission may lack
    std::string cxx, cxxflags, libs; // how to compile and link
    std::string objects;  // a folder of compiled files shared by every submission of the class
    Limits limits;        // for each compiler run
};

// Builds the program of the submission in dir (overlaid on the kit) into work/ray. False with
// *error: the first error the compiler gave, or why it could not run.
bool BuildSubmission(const BuildSettings *settings, const std::string &dir, const std::string &work,
                     std::string *error);

// The kit's own files compiled once into settings->objects, for every submission to share.
void BuildKitObjects(const BuildSettings *settings, int jobs);
