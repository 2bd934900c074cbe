// tests/test_mesh_rays.cpp -- rays at meshes, and the program around them.
//
// Rays fired at a turned quad hit where the pencil says; the committed icosphere is closed,
// wound outward, and never lets a ray out through a corner or an edge; and the program refuses
// to write its image over a mesh it read, as it refuses to write over the scene file.
#include "../app/app.h"
#include "test.h"

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <unistd.h>

// The unit square z = 0 as a quad; its outward side, (b - a) x (c - a), faces +z. The fan makes
// triangle 0 below the diagonal y = x and triangle 1 above it.
static const char *kQuad = "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nf 1 2 3 4\n";

static void Write(const std::string &path, const std::string &text) {
    std::ofstream(path, std::ios::binary) << text;
}

// Rays at the quad, moved by `rotate y 90 translate 0 0 -5`: (x, y, 0) goes to (0, y, -x - 5),
// a square in the plane x = 0 whose outward side faces +x.
static void TestMeshProbes(const std::string &dir) {
    Scene scene;
    std::string error;
    Write(dir + "/quad.obj", kQuad);
    Write(dir + "/p.scene", "material m\ntriangle 0 0 -90  1 0 -90  0 1 -90 m\n"
                            "mesh quad.obj m rotate y 90 translate 0 0 -5\n");
    bool read = ReadSceneFile((dir + "/p.scene").c_str(), &scene, &error);
    CHECK(read, "the probe scene reads (" + error + ")");
    if (!read)
        return;
    struct Probe {
        Ray ray;
        real t;
        int index;
        bool front;
    };
    // From (3, 0.25, -5.5) along -x: x = 0 at t = 3, the quad's point (0.5, 0.25), below y = x:
    // triangle 0 of the mesh, index 1 in the scene. Along -x from (3, 0.25, -4.5): (-0.5, 0.25),
    // above the diagonal: index 2. From behind (x = -2, along +x, d twice as long): t = 1
    const Probe probes[] = {{{{3, 0.25, -5.5}, {-1, 0, 0}}, 3, 1, true},
                            {{{3, 0.25, -4.5}, {-1, 0, 0}}, 3, 2, true},
                            {{{-2, -0.5, -5.25}, {2, 0, 0}}, 1, 1, false}};
    for (const Probe &p : probes) {
        RayHit hit;
        bool found = FindNearestHit(&scene, kRobustMethods, &p.ray, 0, kInfinity, &hit);
        CHECK(found && hit.shape == SHAPE_TRIANGLE && hit.index == p.index &&
                  hit.frontFace == p.front && std::fabs(hit.normal.x) == 1,
              "ray at the turned quad: triangle " + std::to_string(p.index) + ", normal along x");
        CHECK_NEAR(found ? hit.t : -1, p.t, kRelTol * 8, "ray at the turned quad: t predicted");
    }
    Ray past = {{3, 1.5, -5}, {-1, 0, 0}}; // above the square (y = 1.5 > 1): a miss
    RayHit hit;
    CHECK(!FindNearestHit(&scene, kRobustMethods, &past, 0, kInfinity, &hit),
          "a ray passing above the turned quad misses it");
}

// Every edge a -> b of a triangle is met once the other way, b -> a, in exactly one other
// triangle: the surface is closed and its winding consistent. Corners are compared as numbers.
static bool ClosedAndConsistent(const std::vector<Triangle> &triangles) {
    std::map<std::vector<real>, int> edges; // (a, b) -> how often seen
    for (const Triangle &t : triangles) {
        vec3 c[3] = {t.a, t.b, t.c};
        for (int k = 0; k < 3; k++) {
            vec3 a = c[k], b = c[(k + 1) % 3];
            edges[{a.x, a.y, a.z, b.x, b.y, b.z}]++;
        }
    }
    for (const auto &edge : edges) {
        const std::vector<real> &e = edge.first;
        auto reverse = edges.find({e[3], e[4], e[5], e[0], e[1], e[2]});
        if (edge.second != 1 || reverse == edges.end() || reverse->second != 1)
            return false;
    }
    return true;
}

// Rays from `origin`, inside, aimed exactly at every corner and every edge's midpoint: each
// must hit the mesh from inside about where it was aimed (t = 1). Returns how many leak.
static int LeaksFrom(const Scene *scene, vec3 origin) {
    int leaks = 0;
    for (const Triangle &t : scene->triangles) {
        vec3 c[3] = {t.a, t.b, t.c};
        for (int k = 0; k < 3; k++) {
            vec3 targets[2] = {c[k], real(0.5) * (c[k] + c[(k + 1) % 3])};
            for (vec3 target : targets) {
                Ray ray = {origin, target - origin};
                RayHit hit;
                bool found = FindNearestHit(scene, kRobustMethods, &ray, 0, kInfinity, &hit);
                leaks += !found || hit.frontFace || std::fabs(hit.t - 1) > real(1e-3);
            }
        }
    }
    return leaks;
}

// scenes/icosphere.obj (make_mesh sphere 3): 1,280 triangles, closed, wound outward, and no ray
// from inside gets out through a corner or an edge, where two or more triangles meet.
static void TestIcosphereIsClosed() {
    const char *places[] = {"", "rotate x 37 rotate y -12.5 scale 3 translate 100 -50 20"};
    for (const char *words : places) {
        Scene scene;
        std::string error, text = std::string("material m\nmesh icosphere.obj m ") + words + "\n";
        bool read = ParseSceneText(text, "scenes/leak.scene", &scene, &error);
        CHECK(read && scene.triangles.size() == 1280,
              "scenes/icosphere.obj reads as 1,280 triangles (" + error + ")");
        if (!read)
            continue;
        std::vector<std::string> tokens;
        std::vector<MeshStep> steps;
        Tokenize(words, &tokens);
        ParseMeshTransform(tokens, 0, &steps, &error);
        vec3 centre = TransformVertex(steps, {0, 0, 0});
        int inward = 0;
        for (const Triangle &t : scene.triangles)
            inward += Dot(Cross(t.b - t.a, t.c - t.a), (t.a + t.b + t.c) - real(3) * centre) <= 0;
        CHECK(inward == 0 && ClosedAndConsistent(scene.triangles),
              std::string("the icosphere is closed and every face is wound outward ") + words);
        vec3 inside[] = {{0, 0, 0}, {real(0.3), real(-0.2), real(0.1)}, {-0.5, 0.4, 0.25}};
        for (vec3 p : inside) {
            vec3 origin = TransformVertex(steps, p);
            int leaks = LeaksFrom(&scene, origin);
            CHECK(leaks == 0, "rays from inside the icosphere at every corner and edge midpoint "
                              "hit it from inside at t = 1: " +
                                  std::to_string(leaks) + " leak " + words);
        }
    }
}

// The program refuses an output that is a mesh the scene read, as it refuses the scene file.
static void TestMeshInProgram(const std::string &dir) {
    Write(dir + "/quad.obj", kQuad);
    Write(dir + "/s.scene",
          "size 8 8\nmaterial m\nlight 0 0 0\nmesh quad.obj m translate 0 0 -5\n");
    std::string err;
    CHECK(RunRay(dir, "s.scene -o quad.obj", &err) == 2 && ReadFile(dir + "/quad.obj") == kQuad,
          "`ray s.scene -o quad.obj`: exit 2, the mesh untouched (" + err + ")");
    int linked = symlink("quad.obj", (dir + "/picture.png").c_str());
    CHECK(linked == 0 && RunRay(dir, "s.scene -o picture.png", &err) == 2 &&
              err.find("is also an input") != std::string::npos &&
              ReadFile(dir + "/quad.obj") == kQuad,
          "an output linked to the mesh: exit 2, `is also an input`, the mesh untouched (" + err +
              ")");
    CHECK(RunRay(dir, "s.scene -o fine.png", &err) == 0, "the mesh scene renders (" + err + ")");
    CHECK(RunRay(dir, "s.scene --ray 0.5 -0.25 0 0 0 -1", &err) == 0 &&
              ReadFile(dir + "/out.txt").find("\"t\":5,") != std::string::npos &&
              ReadFile(dir + "/out.txt").find("\"shape\":\"triangle\",\"index\":0,") !=
                  std::string::npos,
          "--ray at the quad's lower-right half: t 5, triangle 0 (" + ReadFile(dir + "/out.txt") +
              ")");
    Write(dir + "/bad.obj", "v 0 0 0\nv 1 0 0\r\nf 1 2 3\n");
    Write(dir + "/bad.scene", "material m\nmesh bad.obj m\n");
    CHECK(RunRay(dir, "bad.scene", &err) == 2 &&
              err == "ray: bad.obj:3: f: vertex index 3 is out of range (2 vertices read so far; "
                     "the first is 1)\n",
          "a bad index: `ray: bad.obj:3: ...` (got " + err + ")");
}

void TestMeshRays() {
    std::string dir = MakeTestDir("mesh-rays");
    if (dir.empty())
        return;
    TestMeshProbes(dir);
    TestIcosphereIsClosed();
    TestMeshInProgram(dir);
    RemoveTestDir(dir);
}
