// bench/terminator.cpp -- the shadow terminator of a smooth low-polygon sphere, and what handling
// it costs (`rtbench terminator DIR OBJ...`, part of `make bench`).
//
// Each OBJ (an icosphere with its vertex normals, from tools/make_mesh; its path relative to DIR,
// where the scenes are written) is lit from nearly behind
// its silhouette and drawn at 256 x 256 under `shading floor` three ways, beside the true sphere:
// with the handouts' methods (the shadow ray leaves the flat triangle; the plain loop), with rt's
// but the shadow ray leaving the flat triangle as the handouts' do (`--self-hit skip`: the same
// search, so the time difference is the terminator's alone), and with rt's (it leaves the curved
// surface, Hanika). Over the pixels both the mesh and the sphere show: how many of those the sphere
// lights the mesh leaves dark (shadowed by its own facets), and the share of the sphere's light
// the mesh's image lacks. Times are the render's, median (min-max) of kRounds, the three in turn.
// Appends a table to DIR/terminator.md.
#include "../app/app.h"
#include "../fast/fast.h"
#include "../render.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

static const int kRounds = 5;

static const char *kScene = "size 256 256\ncamera lookat 0 0 3.2  0 0 0  0 1 0  40\n"
                            "shading floor\nambient 0.01\nlight 10 3 -2.5\n"
                            "material m diffuse 1 1 1\n";

// The linear light of every pixel, and the render's time in ms.
static std::vector<double> Pixels(const Scene *scene, Methods methods, double *ms) {
    RenderSettings s = {};
    s.width = scene->width, s.height = scene->height, s.samplesPerPixel = 1;
    s.sampling = SAMPLES_GRID, s.depth = scene->depth, s.threads = 1, s.methods = methods;
    PlanRender(scene, &s);
    std::vector<double> v;
    RayStats stats = {};
    auto start = std::chrono::steady_clock::now();
    for (int j = 0; j < scene->height; j++)
        for (int i = 0; i < scene->width; i++) {
            color c = RenderPixel(scene, &s, i, j, &stats);
            v.push_back((c.x + c.y + c.z) / 3);
        }
    *ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return v;
}

static bool Load(const std::string &path, const std::string &text, Scene *scene,
                 SceneLayout *layout) {
    std::ofstream(path) << text;
    std::string error;
    if (!ReadSceneFile(path.c_str(), scene, &error)) {
        fprintf(stderr, "%s\n", error.c_str());
        return false;
    }
    CommitScene(scene, LAYOUT_AUTO, 1, layout);
    return true;
}

static std::string Spread(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    char text[64];
    snprintf(text, sizeof text, "%.1f (%.1f-%.1f)", v[v.size() / 2], v.front(), v.back());
    return text;
}

int TerminatorTable(const char *folder, char **objs, int count) {
    std::string dir = folder;
    FILE *out = fopen((dir + "/terminator.md").c_str(), "a");
    if (!out)
        return 1;
    fprintf(out, "\n%s: an icosphere at grazing light, 256 x 256, against the true sphere\n\n",
            sizeof(real) == sizeof(double) ? "double" : "float");
    fprintf(out, "| triangles | methods | lit pixels left dark | light lacking | render ms |\n");
    fprintf(out, "|---:|---|---:|---:|---:|\n");
    Scene sphere;
    SceneLayout sphereLayout;
    if (!Load(dir + "/terminator_sphere.scene", std::string(kScene) + "sphere 0 0 0 1 m\n", &sphere,
              &sphereLayout))
        return 1;
    double ignored;
    std::vector<double> truth = Pixels(&sphere, kRobustMethods, &ignored);
    for (int k = 0; k < count; k++) {
        Scene mesh;
        SceneLayout layout;
        if (!Load(dir + "/terminator_mesh.scene", std::string(kScene) + "mesh " + objs[k] + " m\n",
                  &mesh, &layout))
            return 1;
        Methods skip = kRobustMethods;
        skip.selfHit = SELF_HIT_SKIP;
        const Methods ways[3] = {kHandoutMethods, skip, kRobustMethods};
        const char *names[3] = {"the handouts' (`--methods handout`)",
                                "rt's, leaving the flat triangle (`--self-hit skip`)", "rt's"};
        std::vector<double> ms[3], v[3];
        for (int round = 0; round < kRounds; round++)
            for (int way = 0; way < 3; way++) {
                double t;
                v[way] = Pixels(&mesh, ways[way], &t);
                ms[way].push_back(t);
            }
        for (int way = 0; way < 3; way++) {
            int lit = 0, dark = 0;
            double lacks = 0, total = 0;
            for (size_t p = 0; p < truth.size(); p++) {
                if (!(v[way][p] > 0 && truth[p] > 0))
                    continue;
                lit += truth[p] > 0.02, dark += truth[p] > 0.02 && v[way][p] <= 0.011;
                lacks += std::max(0.0, truth[p] - v[way][p]), total += truth[p];
            }
            fprintf(out, "| %zu | %s | %d of %d | %.2f%% | %s |\n", mesh.triangles.size(),
                    names[way], dark, lit, 100 * lacks / total, Spread(ms[way]).c_str());
        }
    }
    fclose(out);
    return 0;
}
