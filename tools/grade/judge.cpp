// tools/grade/judge.cpp -- one scene's verdict, and the line a student reads: how the run ended,
// whether the image matches rt's, and if not, either the known bug whose image it is, or what
// differs in words a student can act on (which shapes are too dark, too bright, missing, or
// drawn where rt sees none) and the pixel to follow.
#include "grade.h"

#include <algorithm>
#include <csignal>
#include <cstdio>
#include <map>
#include <set>
#include <sstream>

const char *VerdictWord(Verdict verdict) {
    static const char *const kWords[] = {"pass",       "differs",    "crashed",
                                         "timed-out",  "exited",     "no-image",
                                         "unreadable", "wrong-size", "not-run",
                                         "not-built"};
    return kWords[verdict];
}

// 1,234 for 1234: counts a student reads.
static std::string Count(long n) {
    std::string s = std::to_string(n);
    for (int at = (int)s.size() - 3; at > 0; at -= 3)
        s.insert((size_t)at, ",");
    return s;
}

// The known bug of the scene whose image the student's matches as closely as a pass would,
// nearest first; nullptr if none does.
static const SetBug *MatchingBug(const SetScene *scene, const Image *image, long allowed) {
    const SetBug *best = nullptr;
    long fewest = allowed + 1;
    for (const SetBug &bug : scene->bugs) {
        ImageDifference d;
        Image heat;
        if (CompareImages(&bug.image, image, kTolerance, &d, &heat) && d.pixelsOver < fewest) {
            best = &bug;
            fewest = d.pixelsOver;
        }
    }
    return best;
}

// The scene file's line `line` (from 1), split into words.
static std::vector<std::string> LineWords(const std::string &text, int line) {
    std::istringstream in(text);
    std::string s;
    for (int k = 0; k < line && std::getline(in, s); k++) {
    }
    std::istringstream words(s);
    std::vector<std::string> out;
    for (std::string w; words >> w;)
        out.push_back(w);
    return out;
}

// How the student's pixels differ from rt's, gathered by what rt sees there: the shapes of one
// kind and material (`the red sphere`), or the background.
struct Group {
    std::string name;
    std::set<int> lines; // the scene's lines that make it (none: the background)
    long pixels = 0, missing = 0, darker = 0, brighter = 0;
    std::map<std::string, long> shows; // pixels that show another group's colour instead
    std::map<uint32_t, long> colours;  // rt's colours in it, to find its usual one
    uint32_t usual = 0;
};

static int LineAt(const Image *shapes, size_t p) {
    return shapes->pixels[3 * p] | shapes->pixels[3 * p + 1] << 8;
}

static uint32_t Rgb(const uint8_t *c) { return (uint32_t)c[0] << 16 | c[1] << 8 | c[2]; }

static bool Near(const uint8_t *a, uint32_t b) {
    for (int c = 0; c < 3; c++)
        if (std::abs(a[c] - (int)(b >> (16 - 8 * c) & 255)) > kTolerance)
            return false;
    return true;
}

// The name of the group of a scene line: its material and kind (the last word and the first).
static std::string GroupName(const std::string &text, int line) {
    std::vector<std::string> words = LineWords(text, line);
    return line == 0 || words.empty() ? "the background" : "the " + words.back() + " " + words[0];
}

// The groups of the scene, each with its pixels, its lines and its usual colour in rt's image.
static std::map<std::string, Group> Gather(const SetScene *scene) {
    std::map<std::string, Group> groups;
    std::map<int, std::string> names;
    for (size_t p = 0; p < scene->shapes.pixels.size() / 3; p++) {
        int line = LineAt(&scene->shapes, p);
        if (!names.count(line))
            names[line] = GroupName(scene->text, line);
        Group *g = &groups[names[line]];
        g->name = names[line];
        if (line > 0)
            g->lines.insert(line);
        g->pixels++;
        g->colours[Rgb(&scene->reference.pixels[3 * p])]++;
    }
    for (auto &g : groups)
        for (const auto &c : g.second.colours)
            if (c.second > g.second.colours[g.second.usual])
                g.second.usual = c.first;
    return groups;
}

// The groups where the student's image differs, most first, each with how.
static std::vector<Group> Groups(const SetScene *scene, const Image *image) {
    std::map<std::string, Group> groups = Gather(scene);
    uint32_t background = groups.count("the background") ? groups["the background"].usual : 0;
    for (size_t p = 0; p < image->pixels.size() / 3; p++) {
        const uint8_t *r = &scene->reference.pixels[3 * p], *s = &image->pixels[3 * p];
        if (Near(s, Rgb(r)))
            continue;
        int line = LineAt(&scene->shapes, p);
        Group *g = &groups[GroupName(scene->text, line)];
        std::string other;
        for (const auto &o : groups)
            if (o.first != g->name && o.first != "the background" && Near(s, o.second.usual))
                other = o.first + (o.second.lines.size() > 1 ? "s" : "");
        if (line > 0 && Near(s, background))
            g->missing++;
        else if (!other.empty())
            g->shows[other]++;
        else
            (s[0] + s[1] + s[2] < r[0] + r[1] + r[2] ? g->darker : g->brighter)++;
    }
    std::vector<Group> out;
    auto wrong = [](const Group &g) {
        long n = g.missing + g.darker + g.brighter;
        for (const auto &o : g.shows)
            n += o.second;
        return n;
    };
    for (const auto &g : groups)
        if (wrong(g.second) > 0)
            out.push_back(g.second);
    std::sort(out.begin(), out.end(), [&](const Group &a, const Group &b) { return wrong(a) > wrong(b); });
    return out;
}

// One group in words: "the red sphere (line 9): 120 of its 800 pixels too dark, 30 show the
// blue triangle".
static std::string Words(const Group *g) {
    bool shape = !g->lines.empty(), several = g->lines.size() > 1;
    std::string name = g->name + (several ? "s" : ""), where;
    if (shape)
        where = several ? " (lines " + std::to_string(*g->lines.begin()) + "-" +
                              std::to_string(*g->lines.rbegin()) + ")"
                        : " (line " + std::to_string(*g->lines.begin()) + ")";
    std::vector<std::string> parts;
    if (g->missing)
        parts.push_back(Count(g->missing) + " missing (the background shows)");
    for (const auto &o : g->shows)
        parts.push_back(Count(o.second) + " show " + o.first);
    if (g->darker)
        parts.push_back(Count(g->darker) + (shape ? " too dark" : " darker"));
    if (g->brighter)
        parts.push_back(Count(g->brighter) + (shape ? " too bright" : " brighter"));
    std::string text = name + where + (several ? ": of their " : ": of its ") + Count(g->pixels) + " pixels, ";
    for (size_t k = 0; k < parts.size(); k++)
        text += (k ? ", " : "") + parts[k];
    return text;
}

// What differs, most first, at most three groups.
static std::string Describe(const SetScene *scene, const Image *image) {
    std::vector<Group> groups = Groups(scene, image);
    std::string text;
    for (size_t k = 0; k < groups.size() && k < 3; k++)
        text += (k ? "; " : "") + Words(&groups[k]);
    return text;
}

// An exit status, and what a shell means by one above 128: a command it ran ended by a signal.
static std::string Status(int status) {
    std::string s = std::to_string(status);
    if (status > 128 && status < 128 + 32)
        s += " (a program it ran ended with " + SignalName(status - 128) + ")";
    return s;
}

// The run's own verdict, where it decides one: it never ended, never started, or left no image.
static bool RunVerdict(const RunResult *run, const Image *image, const std::string &imageError,
                       SceneResult *result) {
    if (run->end == RUN_TIMED_OUT) {
        char text[80];
        snprintf(text, sizeof text, "timed out after %g s (its whole process group was killed)",
                 run->seconds);
        result->verdict = VERDICT_TIMED_OUT, result->text = text;
    } else if (run->end == RUN_NOT_STARTED)
        result->verdict = VERDICT_NOT_RUN, result->text = "could not be run: " + run->why;
    else if (image)
        return false;
    else if (run->end == RUN_SIGNALED)
        result->verdict = VERDICT_CRASHED,
        result->text = "crashed (" + SignalName(run->status) + ")" +
                       (run->status == SIGXFSZ ? ": it wrote a file larger than the limit" : "");
    else if (run->status != 0)
        result->verdict = VERDICT_EXITED,
        result->text = "exited with status " + Status(run->status) + " and " +
                       (imageError.empty() ? "wrote no image" : "an image that cannot be read: " + imageError);
    else
        result->verdict = imageError.empty() ? VERDICT_NO_IMAGE : VERDICT_UNREADABLE,
        result->text = imageError.empty() ? "wrote no image (exit status 0)"
                                          : "its image cannot be read: " + imageError;
    return true;
}

// What the run left to note beside a graded image: an exit status, or a crash after the image.
static std::string RunNote(const RunResult *run) {
    if (run && run->end == RUN_EXITED && run->status != 0)
        return "and it exited with status " + Status(run->status);
    if (run && run->end == RUN_SIGNALED)
        return "and it then crashed: " + SignalName(run->status);
    return "";
}

void Judge(const SetScene *scene, const RunResult *run, const Image *image,
           const std::string &imageError, const std::string &follow, SceneResult *result) {
    *result = {scene->name, VERDICT_PASS, "", 0, 0, {}, {}};
    if (run && RunVerdict(run, image, imageError, result))
        return;
    if (!image) {
        result->verdict = imageError.empty() ? VERDICT_NO_IMAGE : VERDICT_UNREADABLE;
        result->text = imageError.empty() ? "no image " + scene->name + ".png (nor .ppm)"
                                          : "the image cannot be read: " + imageError;
        return;
    }
    const Image *ref = &scene->reference;
    result->image = *image;
    ImageDifference d;
    if (!CompareImages(ref, image, kTolerance, &d, &result->heatmap)) {
        result->verdict = VERDICT_WRONG_SIZE;
        result->text = "the image is " + std::to_string(image->width) + " x " +
                       std::to_string(image->height) + " pixels, the scene's " +
                       std::to_string(ref->width) + " x " + std::to_string(ref->height);
        if (!RunNote(run).empty())
            result->text += " (" + RunNote(run) + ")";
        return;
    }
    long total = (long)ref->width * ref->height;
    result->differing = d.pixelsOver, result->allowed = total / kPassRatio;
    if (d.pixelsOver <= result->allowed) {
        result->text = RunNote(run);
        return;
    }
    result->verdict = VERDICT_DIFFERS;
    const SetBug *bug = MatchingBug(scene, image, result->allowed);
    std::string why = bug ? "looks like " + bug->advice : "unlike rt's: " + Describe(scene, image);
    for (size_t k = 0; bug && k < bug->alike.size(); k++)
        why += "; or " + bug->alike[k];
    const PixelDifference *worst = &d.worst[0];
    result->text = Count(d.pixelsOver) + " of " + Count(total) + " pixels differ" +
                   (RunNote(run).empty() ? "" : " (" + RunNote(run) + ")") + ": " + why;
    if (!follow.empty()) // (a pixel to follow, where the reader has the scene)
        result->text += " (follow one: " + follow + " " + std::to_string(worst->x) + " " +
                        std::to_string(worst->y) + ")";
}
