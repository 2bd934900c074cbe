// bench/peer_rt.cpp -- rt's side of make bench's peer rows (bench/peers.h says what each mode
// prints): the mesh committed (CommitScene, one thread) and searched for the nearest hit
// (FindNearestHit, the robust methods), in double (build/peer_rt) or float (build/peer_rt_float).
// The structure's bytes are the committed layout's (LayoutBytes): the scene's own triangles,
// which every search reads, are not counted, as no library's input is.
#include "../fast/fast.h"
#include "../render.h"
#include "peers.h"

static void MakeScene(const std::vector<float> &v, const std::vector<unsigned> &f, Scene *scene) {
    InitScene(scene);
    scene->materials = {{"white", {1, 1, 1}, {1, 1, 1}, 0, 1, 0, 0, {0, 0, 0}}};
    auto corner = [&](unsigned k) { return vec3{v[3 * k], v[3 * k + 1], v[3 * k + 2]}; };
    scene->triangles.reserve(f.size() / 3);
    for (size_t t = 0; t < f.size(); t += 3)
        scene->triangles.push_back({corner(f[t]), corner(f[t + 1]), corner(f[t + 2]), 0});
}

static bool Trace(const Scene *scene, const float o[3], const float d[3], double *t) {
    Ray ray = {{o[0], o[1], o[2]}, {d[0], d[1], d[2]}};
    RayHit hit;
    bool found = FindNearestHit(scene, kRobustMethods, &ray, 0, kInfinity, &hit);
    *t = found ? (double)hit.t : 0;
    return found;
}

static void Time(const std::vector<float> &v, const std::vector<unsigned> &f, int rounds) {
    auto start = std::chrono::steady_clock::now();
    Scene scene;
    MakeScene(v, f, &scene);
    SceneLayout layout;
    CommitScene(&scene, LAYOUT_AUTO, 1, &layout);
    printf("%.3f\n", peers::Ms(start));
    long hits = peers::TimeEyeRays(
        rounds, [&](const float *o, const float *d, double *t) { return Trace(&scene, o, d, t); });
    printf("hits %ld\nbytes %zu\n", hits, LayoutBytes(&layout));
}

static void Cracks(const std::vector<float> &v, const std::vector<unsigned> &f) {
    Scene scene;
    MakeScene(v, f, &scene);
    SceneLayout layout;
    CommitScene(&scene, LAYOUT_AUTO, 1, &layout);
    peers::PrintCracks(
        v, f, [&](const float *o, const float *d, double *t) { return Trace(&scene, o, d, t); });
}

int main(int argc, char **argv) {
    int rounds;
    int mode = peers::Mode(argc, argv, "peer_rt", &rounds);
    std::vector<float> v;
    std::vector<unsigned> f;
    if (mode < 0 || !peers::ReadObj(argv[2], &v, &f)) {
        if (mode >= 0)
            fprintf(stderr, "peer_rt: cannot read %s\n", argv[2]);
        return 2;
    }
    if (mode == 0)
        Time(v, f, rounds);
    else
        Cracks(v, f);
    return 0;
}
