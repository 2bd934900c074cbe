// bench/report.cpp -- turns a bench run's results.csv into results.md (tables and the conclusions,
// in measured numbers) and accuracy_vs_time.svg (error against time; SVG written by hand).
// Every time is a median with its min and max; two times whose ranges overlap are called the
// same "within noise", whatever the ratio of their medians.
#include "svg.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace {

struct Result {
    std::string scene, knob, setting;
    int spp;
    Spread seconds;
    double rmse, psnr, off1, off8;
    long long rays;
    bool ranged; // min and max recorded (results.csv from an older run has only the median)
};

std::vector<std::string> SplitCsv(const std::string &line) {
    std::vector<std::string> out;
    std::stringstream in(line);
    for (std::string cell; std::getline(in, cell, ',');)
        out.push_back(cell);
    while (out.size() < 12)
        out.push_back("");
    return out;
}

const Result *Find(const std::vector<Result> &rs, const std::string &scene, const std::string &knob,
                   const std::string &setting, int spp) {
    for (const Result &r : rs)
        if (r.scene == scene && r.knob == knob && r.setting == setting && r.spp == spp)
            return &r;
    return nullptr;
}

void Table(std::ostream &md, const std::vector<Result> &rs, const std::string &scene) {
    md << "| knob | setting | spp | seconds, median (min-max) | rays | RMSE | PSNR dB | off > "
          "1/255 | off > 8/255 |\n"
       << "| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n";
    for (const Result &r : rs)
        if (r.scene == scene)
            md << Format(
                "| %s | %s | %d | %s | %lld | %.3f | %.1f | %.2f%% | %.3f%% |\n", r.knob.c_str(),
                r.setting.c_str(), r.spp,
                (r.ranged ? SpreadText(r.seconds, "%.4f") : Format("%.4f", r.seconds.median))
                    .c_str(),
                r.rays, r.rmse, r.psnr, 100 * r.off1, 100 * r.off8);
    md << "\n";
}

// "0.0256 s, 0.0251-0.0263": a time's median and range.
std::string Seconds(const Spread &t) { return Format("%.3g s, %.3g-%.3g", t.median, t.min, t.max); }

// "A takes P% of the time of B (times)", or, when their ranges overlap, "A and B take the same
// time within noise (ratio of medians R; times)".
std::string Versus(const Result *a, const Result *b, const char *aName, const char *bName) {
    double ratio = a->seconds.median / b->seconds.median;
    if (!a->ranged || !b->ranged)
        return Format("the ratio of the medians of %s and %s is %.2f (no min and max recorded: "
                      "no conclusion)",
                      aName, bName, ratio);
    std::string times = Seconds(a->seconds) + ", against " + Seconds(b->seconds);
    if (WithinNoise(a->seconds, b->seconds))
        return Format("%s and %s take the same time within noise (ratio of medians %.2f; %s)",
                      aName, bName, ratio, times.c_str());
    return Format("%s takes %.0f%% of the time of %s (%s)", aName, 100 * ratio, bName,
                  times.c_str());
}

// One sentence per knob, in measured numbers.
void Conclusions(std::ostream &md, const std::vector<Result> &rs, const std::string &scene) {
    const Result *g16 = Find(rs, scene, "aa", "grid", 16),
                 *a16 = Find(rs, scene, "aa", "adaptive", 16),
                 *g64 = Find(rs, scene, "aa", "grid", 64),
                 *j16 = Find(rs, scene, "aa", "jitter", 16),
                 *d1 = Find(rs, scene, "precision", "double", 1),
                 *f1 = Find(rs, scene, "precision", "float", 1),
                 *d16 = Find(rs, scene, "precision", "double", 16),
                 *f16 = Find(rs, scene, "precision", "float", 16),
                 *cr = Find(rs, scene, "triangle", "cramer", 1),
                 *wt = Find(rs, scene, "triangle", "watertight", 1),
                 *tb = Find(rs, scene, "sphere", "textbook", 1),
                 *st = Find(rs, scene, "sphere", "stable", 1),
                 *dep1 = Find(rs, scene, "depth", "1", 1),
                 *dep10 = Find(rs, scene, "depth", "10", 1),
                 *fDiff = Find(rs, scene, "difference", "float", 1),
                 *crDiff = Find(rs, scene, "difference", "cramer", 1),
                 *tbDiff = Find(rs, scene, "difference", "textbook", 1);
    md << "**" << scene << " scene.**\n\n";
    if (g16 && a16 && g64)
        md << Format("- Anti-aliasing: adaptive 16 spp has RMSE %.3f against grid 16 spp's %.3f, "
                     "%.0f%% of the error of grid 64 spp (%.3f); jitter 16 spp: RMSE %.3f. In "
                     "time, %s; %s.\n",
                     a16->rmse, g16->rmse, 100 * a16->rmse / g64->rmse, g64->rmse,
                     j16 ? j16->rmse : NAN,
                     Versus(a16, g16, "adaptive 16 spp", "grid 16 spp").c_str(),
                     Versus(a16, g64, "adaptive 16 spp", "grid 64 spp").c_str());
    if (d1 && f1 && d16 && f16 && fDiff)
        md << Format("- Precision: at 1 spp %s; at 16 spp %s. Float's image differs from double's "
                     "in %.3f%% of the pixels by more than 1/255 and in %.4f%% by more than "
                     "8/255 (heat map `%s_float_vs_double.png`); against the converged reference "
                     "float has RMSE %.3f and double %.3f: at this scale precision is far below "
                     "aliasing.\n",
                     Versus(f1, d1, "float", "double").c_str(),
                     Versus(f16, d16, "float", "double").c_str(), 100 * fDiff->off1,
                     100 * fDiff->off8, scene.c_str(), f1->rmse, d1->rmse);
    if (cr && wt && crDiff)
        md << Format("- Triangles, both in the plain loop: %s. Cramer's image differs from the "
                     "watertight one in %.4f%% "
                     "of the pixels by more than 1/255: at scale 1 these are ties, rays exactly "
                     "through an edge two triangles share that take the other one, both right "
                     "(`rtbench methods` sorts them); Cramer's real cracks are what the hard-case "
                     "suite below counts.\n",
                     Versus(wt, cr, "the watertight default", "the handout's Cramer form").c_str(),
                     100 * crDiff->off1);
    if (tb && st && tbDiff)
        md << Format("- Spheres, both in the plain loop: %s. The textbook image differs from the "
                     "stable one in %.3f%% of "
                     "the pixels by more than 1/255 (RMSE against the reference %.3f, stable "
                     "%.3f; heat map `%s_textbook_sphere.png`).\n",
                     Versus(st, tb, "the stable form", "the textbook quadratic").c_str(),
                     100 * tbDiff->off1, tb->rmse, st->rmse, scene.c_str());
    if (dep1 && dep10)
        md << Format("- Depth: one ray per chain (no reflections) has RMSE %.3f; %s.\n\n",
                     dep1->rmse, Versus(dep1, dep10, "depth 1", "depth 10").c_str());
}

const char *kMethods[] = {"grid", "jitter", "adaptive"};
const char *kColors[] = {"#1f77b4", "#ff7f0e", "#2ca02c"};

// A sampling method's points: 1 spp (the one-sample image, shared) and 4, 16 and 64 spp.
std::vector<const Result *> MethodPoints(const std::vector<Result> &rs, const char *scene, int m) {
    std::vector<const Result *> out;
    for (int spp : {1, 4, 16, 64})
        if (const Result *r = spp == 1 ? Find(rs, scene, "precision", "double", 1)
                                       : Find(rs, scene, "aa", kMethods[m], spp))
            out.push_back(r);
    return out;
}

// The red squares: float, Cramer triangles and textbook spheres.
std::vector<std::pair<const Result *, std::string>> Marks(const std::vector<Result> &rs,
                                                          const char *scene) {
    const char *knobs[][3] = {{"precision", "float", "float"},
                              {"triangle", "cramer", "Cramer"},
                              {"sphere", "textbook", "textbook sphere"}};
    std::vector<std::pair<const Result *, std::string>> out;
    for (const auto &k : knobs)
        for (int spp : {1, 16})
            if (const Result *r = Find(rs, scene, k[0], k[1], spp))
                out.push_back({r, Format("%s %d", k[2], spp)});
    return out;
}

// A sampling method's line: its points (a whisker from the fastest to the slowest render) and,
// on the grid's line, the sample counts to write by them.
std::string MethodLine(const std::vector<Result> &rs, const char *scene, int m, const SvgAxis &x,
                       const SvgAxis &y, SvgLabels *labels, std::vector<SvgMark> *names) {
    std::string points, marks;
    double lastX = -1, lastY = -1;
    for (const Result *r : MethodPoints(rs, scene, m)) {
        double px = AxisPixel(x, r->seconds.median), py = AxisPixel(y, r->rmse);
        double lo = AxisPixel(x, r->seconds.min), hi = AxisPixel(x, r->seconds.max);
        if (lastX >= 0)
            AddLine(labels, lastX, lastY, px, py, false);
        lastX = px, lastY = py;
        points += Format("%.1f,%.1f ", px, py);
        marks += Format("<line x1='%.1f' y1='%.1f' x2='%.1f' y2='%.1f' stroke='%s'/>\n<circle "
                        "cx='%.1f' cy='%.1f' r='3' fill='%s'/>\n",
                        lo, py, hi, py, kColors[m], px, py, kColors[m]);
        AddMarker(labels, px, py, 3), AddLine(labels, lo, py, hi, py, true);
        if (m == 0)
            names->push_back({px, py, 3, std::to_string(r->spp), "black", 11});
    }
    return Format("<polyline fill='none' stroke='%s' stroke-width='2' points='%s'/>\n", kColors[m],
                  points.c_str()) +
           marks;
}

// One panel, its frame from x0 to x0 + 380 and from 40 to 310: RMSE against time, log-log, a
// line per sampling method, a whisker from the fastest to the slowest render of each point.
std::string Panel(const std::vector<Result> &rs, const char *scene, double x0, SvgLabels *labels) {
    double tMin = 1e30, tMax = 0, eMin = 1e30, eMax = 0;
    for (const Result &r : rs)
        if (r.scene == scene && r.rmse > 0 && r.knob != "difference" && r.knob != "depth")
            tMin = std::min(tMin, r.seconds.min), tMax = std::max(tMax, r.seconds.max),
            eMin = std::min(eMin, r.rmse), eMax = std::max(eMax, r.rmse);
    if (tMax <= 0)
        return "";
    SvgAxis x = FitAxis(tMin, tMax, true, x0, x0 + 380), y = FitAxis(eMin, eMax, true, 310, 40);
    *labels = {FrameBox(x, y), {}, {}, {}, {}, {}, {}};
    std::string out = Format("<text x='%.0f' y='20' font-size='14'>%s scene: RMSE against render "
                             "time</text>\n",
                             x0, scene) +
                      SvgFrame(x, y, "render time, s (log; median, line from min to max)",
                               "RMSE, 8-bit levels (log)");
    std::vector<SvgMark> names;
    for (int m = 0; m < 3; m++)
        out += MethodLine(rs, scene, m, x, y, labels, &names);
    for (const auto &mark : Marks(rs, scene)) {
        const Result *r = mark.first;
        double px = AxisPixel(x, r->seconds.median), py = AxisPixel(y, r->rmse);
        double lo = AxisPixel(x, r->seconds.min), hi = AxisPixel(x, r->seconds.max);
        out += Format("<line x1='%.1f' y1='%.1f' x2='%.1f' y2='%.1f' stroke='#d62728'/>\n<rect "
                      "x='%.1f' y='%.1f' width='6' height='6' fill='#d62728'/>\n",
                      lo, py, hi, py, px - 3, py - 3);
        AddMarker(labels, px, py, 4), AddLine(labels, lo, py, hi, py, true);
        names.push_back({px, py, 4, mark.second, "#d62728", 11});
    }
    return out + PlaceLabels(labels, names);
}
// Error against time on log-log axes, a panel per scene; under them the key, and each panel's
// lettered labels where there was no room for the words.
void Plot(const std::string &path, const std::vector<Result> &rs) {
    const char *scenes[] = {"assignment", "test"};
    SvgLabels labels[2];
    std::string panels;
    for (int p = 0; p < 2; p++)
        panels += Panel(rs, scenes[p], 90 + 480 * p, &labels[p]);
    size_t lines = std::max(labels[0].legend.size(), labels[1].legend.size());
    int height = 392 + 16 * (int)lines;
    std::ofstream svg(path);
    svg << Format("<svg xmlns='http://www.w3.org/2000/svg' width='970' height='%d' "
                  "font-family='sans-serif' font-size='12'>\n<rect width='100%%' height='100%%' "
                  "fill='white'/>\n",
                  height)
        << panels;
    double x = 90;
    for (int m = 0; m < 3; m++, x += 90)
        svg << Format("<line x1='%.0f' y1='366' x2='%.0f' y2='366' stroke='%s' stroke-width='2'/>"
                      "<text x='%.0f' y='370' fill='%s'>%s</text>\n",
                      x, x + 16, kColors[m], x + 20, kColors[m], kMethods[m]);
    svg << Format("<rect x='%.0f' y='363' width='6' height='6' fill='#d62728'/><text x='%.0f' "
                  "y='370'>float, Cramer triangles, textbook spheres; black numbers: spp of the "
                  "grid line</text>\n",
                  x, x + 10);
    for (int p = 0; p < 2; p++)
        svg << SvgLegend(labels[p], 90 + 480 * p, 390, 16);
    svg << "</svg>\n";
}

} // namespace

int ReportMain(const std::string &dir) {
    std::ifstream in(dir + "/results.csv");
    std::vector<Result> rs;
    std::vector<std::string> suite;
    std::string line;
    std::getline(in, line); // header
    while (std::getline(in, line)) {
        std::vector<std::string> c = SplitCsv(line);
        if (c[0] == "hard_cases") {
            suite.push_back(c[2]);
            continue;
        }
        double seconds = atof(c[4].c_str());
        bool ranged = !c[10].empty() && !c[11].empty();
        Spread t = {seconds, ranged ? atof(c[10].c_str()) : seconds,
                    ranged ? atof(c[11].c_str()) : seconds};
        rs.push_back({c[0], c[1], c[2], atoi(c[3].c_str()), t, atof(c[6].c_str()),
                      atof(c[7].c_str()), atof(c[8].c_str()), atof(c[9].c_str()),
                      atoll(c[5].c_str()), ranged});
    }
    if (rs.empty()) {
        fprintf(stderr, "bench: %s/results.csv has no rows\n", dir.c_str());
        return 2;
    }
    std::ofstream md(dir + "/results.md");
    md << "# What accuracy costs in time\n\nWritten by `make bench` from `results.csv`. Errors are "
          "against a converged reference (double, 256 samples per pixel on a grid); RMSE in 8-bit "
          "levels; times are the median (min-max) of at least 5 renders (and of as many as fit in "
          "a "
          "second) on all cores, render only; two times whose ranges overlap are the same within "
          "noise. The assignment scene is rendered at 512 x 512, the test scene at 256 x "
          "256.\n\n## Conclusions\n\n";
    Conclusions(md, rs, "assignment");
    Conclusions(md, rs, "test");
    md << "## Numerical hard cases (rows of the catalogue passed)\n\n| routines and precision | "
          "passed |\n| --- | --- |\n";
    for (const std::string &s : suite) {
        size_t space = s.rfind(' ');
        md << "| " << s.substr(0, space) << " | " << s.substr(space + 1) << " |\n";
    }
    md << "\n## Assignment scene\n\n";
    Table(md, rs, "assignment");
    md << "## Test scene\n\n";
    Table(md, rs, "test");
    Plot(dir + "/accuracy_vs_time.svg", rs);
    fprintf(stderr, "bench: wrote %s/results.md and %s/accuracy_vs_time.svg\n", dir.c_str(),
            dir.c_str());
    return 0;
}
