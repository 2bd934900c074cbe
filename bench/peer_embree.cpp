// bench/peer_embree.cpp -- rt's triangle search beside Embree's (`make bench`, where Embree 3 is
// installed: Debian's libembree-dev; bench/bench.sh builds this as build/peer_embree).
//
//   peer_embree rt|embree MESH.obj ROUNDS
//
// reads the mesh (v and f lines, as tools/make_mesh writes them), builds the one program's
// structure over it, and casts the same 512 x 512 rays from the eye ROUNDS times: rt's nearest
// hit (FindNearestHit through the committed scene, double, watertight) or Embree's rtcIntersect1
// (float, its default build quality). Prints the build's ms, then each round's ms, one a line,
// then the hits of the last round (both programs must agree on how many rays hit). The peak
// memory of the whole process is bench.sh's to read (rtbench timemem), so each program runs alone.
#include "../fast/fast.h"
#include "../render.h"

#include <embree3/rtcore.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

static const int kSize = 512;

static double Ms(std::chrono::steady_clock::time_point since) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - since)
        .count();
}

// The mesh's vertices and faces (1-based indices in the file, 0-based here).
static bool ReadObj(const char *path, std::vector<float> *v, std::vector<unsigned> *f) {
    FILE *file = fopen(path, "r");
    if (!file)
        return false;
    char line[256];
    while (fgets(line, sizeof line, file)) {
        float x, y, z;
        unsigned a, b, c;
        if (sscanf(line, "v %f %f %f", &x, &y, &z) == 3)
            v->insert(v->end(), {x, y, z});
        else if (sscanf(line, "f %u %u %u", &a, &b, &c) == 3)
            f->insert(f->end(), {a - 1, b - 1, c - 1});
    }
    fclose(file);
    return !f->empty();
}

// Ray (i, j) of the image: from (0, 0, 1.8) through a screen of width 1.2 at z = 0.8, toward the
// unit sphere at the origin, which fills the picture but for its corners.
static void EyeRay(int i, int j, float o[3], float d[3]) {
    o[0] = 0, o[1] = 0, o[2] = 1.8f;
    d[0] = 1.2f * (i + 0.5f) / kSize - 0.6f, d[1] = 0.6f - 1.2f * (j + 0.5f) / kSize, d[2] = -1;
}

static int RunRt(const std::vector<float> &v, const std::vector<unsigned> &f, int rounds) {
    auto start = std::chrono::steady_clock::now();
    Scene scene;
    InitScene(&scene);
    scene.materials = {{"white", {1, 1, 1}, {1, 1, 1}, 0, 1, 0, 0, {0, 0, 0}}};
    auto corner = [&](unsigned k) { return vec3{v[3 * k], v[3 * k + 1], v[3 * k + 2]}; };
    for (size_t t = 0; t < f.size(); t += 3)
        scene.triangles.push_back({corner(f[t]), corner(f[t + 1]), corner(f[t + 2]), 0});
    SceneLayout layout;
    CommitScene(&scene, LAYOUT_AUTO, 1, &layout);
    printf("%.3f\n", Ms(start));
    long hits = 0;
    for (int r = 0; r < rounds; r++) {
        start = std::chrono::steady_clock::now();
        hits = 0;
        for (int j = 0; j < kSize; j++)
            for (int i = 0; i < kSize; i++) {
                float o[3], d[3];
                EyeRay(i, j, o, d);
                Ray ray = {{o[0], o[1], o[2]}, {d[0], d[1], d[2]}};
                RayHit hit;
                hits += FindNearestHit(&scene, kRobustMethods, &ray, 0, kInfinity, &hit);
            }
        printf("%.3f\n", Ms(start));
    }
    printf("hits %ld\n", hits);
    return 0;
}

static int RunEmbree(const std::vector<float> &v, const std::vector<unsigned> &f, int rounds) {
    auto start = std::chrono::steady_clock::now();
    RTCDevice device = rtcNewDevice("threads=1");
    RTCScene scene = rtcNewScene(device);
    RTCGeometry mesh = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    float *vertices = (float *)rtcSetNewGeometryBuffer(mesh, RTC_BUFFER_TYPE_VERTEX, 0,
                                                       RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                                                       v.size() / 3);
    unsigned *faces = (unsigned *)rtcSetNewGeometryBuffer(mesh, RTC_BUFFER_TYPE_INDEX, 0,
                                                          RTC_FORMAT_UINT3, 3 * sizeof(unsigned),
                                                          f.size() / 3);
    memcpy(vertices, v.data(), v.size() * sizeof(float));
    memcpy(faces, f.data(), f.size() * sizeof(unsigned));
    rtcCommitGeometry(mesh);
    rtcAttachGeometry(scene, mesh);
    rtcReleaseGeometry(mesh);
    rtcCommitScene(scene);
    printf("%.3f\n", Ms(start));
    long hits = 0;
    for (int r = 0; r < rounds; r++) {
        start = std::chrono::steady_clock::now();
        hits = 0;
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        for (int j = 0; j < kSize; j++)
            for (int i = 0; i < kSize; i++) {
                RTCRayHit rh;
                float o[3], d[3];
                EyeRay(i, j, o, d);
                rh.ray.org_x = o[0], rh.ray.org_y = o[1], rh.ray.org_z = o[2];
                rh.ray.dir_x = d[0], rh.ray.dir_y = d[1], rh.ray.dir_z = d[2];
                rh.ray.tnear = 0, rh.ray.tfar = 1e30f, rh.ray.time = 0;
                rh.ray.mask = ~0u, rh.ray.id = 0, rh.ray.flags = 0;
                rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
                rtcIntersect1(scene, &context, &rh);
                hits += rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
            }
        printf("%.3f\n", Ms(start));
    }
    printf("hits %ld\n", hits);
    rtcReleaseScene(scene);
    rtcReleaseDevice(device);
    return 0;
}

int main(int argc, char **argv) {
    std::vector<float> v;
    std::vector<unsigned> f;
    int rounds = argc == 4 ? atoi(argv[3]) : 0;
    if (argc != 4 || rounds < 1 || !ReadObj(argv[2], &v, &f)) {
        fprintf(stderr, "usage: peer_embree rt|embree MESH.obj ROUNDS\n");
        return 2;
    }
    if (!strcmp(argv[1], "rt"))
        return RunRt(v, f, rounds);
    if (!strcmp(argv[1], "embree"))
        return RunEmbree(v, f, rounds);
    fprintf(stderr, "usage: peer_embree rt|embree MESH.obj ROUNDS\n");
    return 2;
}
