// bench/report.cpp -- turns a bench run's results.csv into results.md (tables and the conclusions,
// in measured numbers) and accuracy_vs_time.svg (error against time; SVG written by hand).
#include <algorithm>
#include <cmath>
#include <cstdarg>
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
    double seconds, rmse, psnr, off1, off8;
    long long rays;
};

std::vector<std::string> SplitCsv(const std::string &line) {
    std::vector<std::string> out;
    std::stringstream in(line);
    for (std::string cell; std::getline(in, cell, ',');)
        out.push_back(cell);
    while (out.size() < 10)
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

std::string Format(const char *format, ...) __attribute__((format(printf, 1, 2)));
std::string Format(const char *format, ...) {
    char text[512];
    va_list args;
    va_start(args, format);
    vsnprintf(text, sizeof text, format, args);
    va_end(args);
    return text;
}

void Table(std::ostream &md, const std::vector<Result> &rs, const std::string &scene) {
    md << "| knob | setting | spp | seconds | rays | RMSE | PSNR dB | off > 1/255 | off > 8/255 |\n"
       << "| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n";
    for (const Result &r : rs)
        if (r.scene == scene)
            md << Format("| %s | %s | %d | %.4f | %lld | %.3f | %.1f | %.2f%% | %.3f%% |\n",
                         r.knob.c_str(), r.setting.c_str(), r.spp, r.seconds, r.rays, r.rmse,
                         r.psnr, 100 * r.off1, 100 * r.off8);
    md << "\n";
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
        md << Format("- Anti-aliasing: adaptive 16 spp has RMSE %.3f against grid 16 spp's %.3f in "
                     "%.0f%% of its time; it reaches %.0f%% of the error of grid 64 spp (%.3f) in "
                     "%.0f%% of its time. Jitter 16 spp: RMSE %.3f.\n",
                     a16->rmse, g16->rmse, 100 * a16->seconds / g16->seconds,
                     100 * a16->rmse / g64->rmse, g64->rmse, 100 * a16->seconds / g64->seconds,
                     j16 ? j16->rmse : NAN);
    if (d1 && f1 && d16 && f16 && fDiff)
        md << Format("- Precision: float takes %.0f%% of double's time at 1 spp and %.0f%% at 16 "
                     "spp. Its image differs from double's in %.3f%% of the pixels by more than "
                     "1/255 and in %.4f%% by more than 8/255 (heat map "
                     "`%s_float_vs_double.png`); against the converged reference float has RMSE "
                     "%.3f and double %.3f: at this scale precision is far below aliasing.\n",
                     100 * f1->seconds / d1->seconds, 100 * f16->seconds / d16->seconds,
                     100 * fDiff->off1, 100 * fDiff->off8, scene.c_str(), f1->rmse, d1->rmse);
    if (cr && wt && crDiff)
        md << Format(
            "- Triangles: the watertight default takes %.0f%% of the time of the handout's "
            "Cramer form (%+.0f%%). Cramer's image differs from the watertight one in "
            "%.4f%% of the pixels by more than 1/255: at scale 1 these are ties, rays exactly "
            "through an edge two triangles share that take the other one, both right (`rtbench "
            "methods` sorts them); Cramer's real cracks are what the hard-case suite below "
            "counts.\n",
            100 * wt->seconds / cr->seconds, 100 * (wt->seconds / cr->seconds - 1),
            100 * crDiff->off1);
    if (tb && st && tbDiff)
        md << Format(
            "- Spheres: the stable form takes %.0f%% of the textbook quadratic's time. The "
            "textbook image differs from the stable one in %.3f%% of the pixels by more "
            "than 1/255 (RMSE against the reference %.3f, stable %.3f; heat map "
            "`%s_textbook_sphere.png`).\n",
            100 * st->seconds / tb->seconds, 100 * tbDiff->off1, tb->rmse, st->rmse, scene.c_str());
    if (dep1 && dep10)
        md << Format(
            "- Depth: one ray per chain (no reflections) has RMSE %.3f and takes %.0f%% of "
            "depth 10's time.\n\n",
            dep1->rmse, 100 * dep1->seconds / dep10->seconds);
}

// Error against time on log-log axes, one polyline per sampling method, points for the rest.
void Plot(const std::string &path, const std::vector<Result> &rs) {
    const int panelW = 440, panelH = 320, left = 60, top = 40;
    std::ofstream svg(path);
    svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << 2 * panelW + 40 << "\" height=\""
        << panelH + 120 << "\" font-family=\"sans-serif\" font-size=\"12\">\n"
        << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
    const char *scenes[] = {"assignment", "test"};
    const char *methods[] = {"grid", "jitter", "adaptive"};
    const char *colors[] = {"#1f77b4", "#ff7f0e", "#2ca02c"};
    for (int p = 0; p < 2; p++) {
        double tMin = 1e9, tMax = 0, eMin = 1e9, eMax = 0;
        for (const Result &r : rs)
            if (r.scene == scenes[p] && r.rmse > 0 && r.knob != "difference") {
                tMin = std::min(tMin, r.seconds), tMax = std::max(tMax, r.seconds);
                eMin = std::min(eMin, r.rmse), eMax = std::max(eMax, r.rmse);
            }
        if (tMax <= 0)
            continue;
        double lt0 = std::floor(std::log10(tMin)), lt1 = std::ceil(std::log10(tMax));
        double le0 = std::floor(std::log10(eMin)), le1 = std::ceil(std::log10(eMax));
        int x0 = p * (panelW + 20) + left, w = panelW - left - 10, h = panelH - 40;
        auto X = [&](double t) { return x0 + w * (std::log10(t) - lt0) / (lt1 - lt0); };
        auto Y = [&](double e) { return top + h - h * (std::log10(e) - le0) / (le1 - le0); };
        svg << Format("<text x=\"%d\" y=\"20\" font-size=\"14\">%s scene: RMSE (8-bit levels) "
                      "against render time</text>\n",
                      x0, scenes[p]);
        svg << Format("<rect x=\"%d\" y=\"%d\" width=\"%d\" height=\"%d\" fill=\"none\" "
                      "stroke=\"#888\"/>\n",
                      x0, top, w, h);
        for (double l = lt0; l <= lt1; l++)
            svg << Format("<text x=\"%.0f\" y=\"%d\" text-anchor=\"middle\">%g s</text>\n",
                          X(std::pow(10, l)), top + h + 16, std::pow(10, l));
        for (double l = le0; l <= le1; l++)
            svg << Format("<text x=\"%d\" y=\"%.0f\" text-anchor=\"end\">%g</text>\n", x0 - 4,
                          Y(std::pow(10, l)) + 4, std::pow(10, l));
        for (int m = 0; m < 3; m++) {
            std::string points;
            for (int spp : {1, 4, 16, 64}) {
                const Result *r = spp == 1 ? Find(rs, scenes[p], "precision", "double", 1)
                                           : Find(rs, scenes[p], "aa", methods[m], spp);
                if (!r)
                    continue;
                points += Format("%.1f,%.1f ", X(r->seconds), Y(r->rmse));
                svg << Format("<circle cx=\"%.1f\" cy=\"%.1f\" r=\"3\" fill=\"%s\"/>\n",
                              X(r->seconds), Y(r->rmse), colors[m]);
                if (m == 0)
                    svg << Format("<text x=\"%.1f\" y=\"%.1f\" font-size=\"10\">%d</text>\n",
                                  X(r->seconds) + 4, Y(r->rmse) - 4, spp);
            }
            svg << "<polyline fill=\"none\" stroke=\"" << colors[m]
                << "\" stroke-width=\"2\" points=\"" << points << "\"/>\n";
            svg << Format("<text x=\"%d\" y=\"%d\" fill=\"%s\">%s</text>\n", x0 + 10 + 80 * m,
                          panelH + 30, colors[m], methods[m]);
        }
        const struct {
            const char *knob, *setting, *label;
        } marks[] = {{"precision", "float", "float"},
                     {"triangle", "cramer", "Cramer"},
                     {"sphere", "textbook", "textbook sphere"}};
        for (int k = 0; k < 3; k++)
            for (int spp : {1, 16})
                if (const Result *r = Find(rs, scenes[p], marks[k].knob, marks[k].setting, spp)) {
                    svg << Format(
                        "<rect x=\"%.1f\" y=\"%.1f\" width=\"6\" height=\"6\" fill=\"#d62728\"/>\n",
                        X(r->seconds) - 3, Y(r->rmse) - 3);
                    svg << Format("<text x=\"%.1f\" y=\"%.1f\" font-size=\"10\" "
                                  "fill=\"#d62728\">%s %d</text>\n",
                                  X(r->seconds) + 5, Y(r->rmse) + 14 + 11 * k, marks[k].label, spp);
                }
    }
    svg << Format("<text x=\"%d\" y=\"%d\">lines: spp 1, 4, 16, 64 for each sampling method; "
                  "red squares: float, Cramer triangles, textbook spheres</text>\n",
                  left, panelH + 60);
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
        rs.push_back({c[0], c[1], c[2], atoi(c[3].c_str()), atof(c[4].c_str()), atof(c[6].c_str()),
                      atof(c[7].c_str()), atof(c[8].c_str()), atof(c[9].c_str()),
                      atoll(c[5].c_str())});
    }
    if (rs.empty()) {
        fprintf(stderr, "bench: %s/results.csv has no rows\n", dir.c_str());
        return 2;
    }
    std::ofstream md(dir + "/results.md");
    md << "# What accuracy costs in time\n\nWritten by `make bench` from `results.csv`. Errors are "
          "against a converged reference (double, 256 samples per pixel on a grid); RMSE in 8-bit "
          "levels; times are medians of at least 5 renders (and of as many as fit in a second) on "
          "all cores, render only. The assignment "
          "scene is rendered at 512 x 512, the test scene at 256 x 256.\n\n## Conclusions\n\n";
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
