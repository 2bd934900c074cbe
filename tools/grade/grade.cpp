// tools/grade/grade.cpp -- a student's program, or a folder of its images, graded scene by scene.
// Each run has a scratch folder of its own holding only the scene; the image is read back from
// there, a regular file no larger than the run could write, and the folder is removed.
#include "grade.h"

#include <sys/stat.h>

// The command that prints a pixel's ray tree in the scene `name`, up to `--pixel`.
static std::string Follow(const GradeOptions *options, const std::string &name) {
    std::string follow = options->follow;
    size_t at = follow.find("{scene}");
    if (at != std::string::npos)
        follow.replace(at, 7, name);
    return follow;
}

// The image at path, if there is one: true with *image, or false with *error ("" when there is
// no file at all). A link is not followed: a program's image is a file it wrote.
static bool ReadStudentImage(const std::string &path, long maxBytes, Image *image, std::string *error) {
    struct stat info;
    error->clear();
    if (lstat(path.c_str(), &info) != 0)
        return false;
    if (!S_ISREG(info.st_mode))
        *error = path.substr(path.find_last_of('/') + 1) + " is not a file (a link, or a folder)";
    else if (info.st_size > maxBytes)
        *error = "it is " + std::to_string((long long)info.st_size) + " bytes, larger than the limit";
    else if (!ReadImage(path.c_str(), image, error))
        *error = error->substr(error->find_last_of('/') + 1);
    else
        return true;
    return false;
}

static bool Chosen(const GradeOptions *options, const SetScene *scene) {
    return options->onlyScene.empty() || options->onlyScene == scene->name;
}

std::vector<SceneResult> GradeProgram(const ReferenceSet *set, const std::vector<std::string> &command,
                                      const GradeOptions *options) {
    std::vector<SceneResult> results;
    for (const SetScene &scene : set->scenes) {
        if (!Chosen(options, &scene))
            continue;
        SceneResult result;
        std::string dir, error, file = scene.name + ".scene", out = scene.name + ".png";
        RunResult run = {RUN_NOT_STARTED, 0, "", "", 0};
        if (!MakeScratch("rt-grade-", &dir, &run.why) ||
            !WriteTextFile(dir + "/" + file, scene.text, &run.why)) {
            Judge(&scene, &run, nullptr, "", "", &result);
            results.push_back(result);
            continue;
        }
        std::vector<std::string> argv = command;
        argv.insert(argv.end(), {file, "-o", out});
        RunLimited(argv, dir, &options->limits, &run);
        Image image;
        bool read = ReadStudentImage(dir + "/" + out, options->limits.outputBytes, &image, &error);
        Judge(&scene, &run, read ? &image : nullptr, error, Follow(options, scene.name), &result);
        RemoveTree(dir);
        results.push_back(result);
    }
    return results;
}

std::vector<SceneResult> GradeImages(const ReferenceSet *set, const std::string &dir,
                                     const GradeOptions *options) {
    std::vector<SceneResult> results;
    for (const SetScene &scene : set->scenes) {
        if (!Chosen(options, &scene))
            continue;
        SceneResult result;
        Image image;
        std::string error, path = dir + "/" + scene.name + ".png";
        struct stat info;
        if (lstat(path.c_str(), &info) != 0)
            path = dir + "/" + scene.name + ".ppm";
        bool read = ReadStudentImage(path, 1L << 28, &image, &error);
        Judge(&scene, nullptr, read ? &image : nullptr, error, Follow(options, scene.name), &result);
        results.push_back(result);
    }
    return results;
}
