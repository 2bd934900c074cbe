// tests/hard_cases_offset.cpp -- the self-intersection (OFF) hard cases: no ray that leaves a
// surface hits it again, at any distance from the origin and at any scale.
#include "hard_cases_suite.h"

// A scene of one triangle, for the shadow rays that leave it (ShadowRay reads its corners).
static Scene OneTriangle(const Triangle &t) {
    Scene scene;
    InitScene(&scene);
    scene.triangles.push_back(t);
    return scene;
}

// Shadow rays from points on a triangle toward a light on the same side: none may hit it again.
static int SelfShadowed(const Suite *s, const Triangle &ground, vec3 eye, vec3 light, int rays,
                        uint64_t seed) {
    SweepRng rng = {seed};
    Scene scene = OneTriangle(ground);
    int acne = 0;
    for (int k = 0; k < rays; k++) {
        double b1 = 1.0 / 3 + (rng.Next() - 0.5) * 0.1, b2 = 1.0 / 3 + (rng.Next() - 0.5) * 0.1;
        vec3 target = real(1 - b1 - b2) * ground.a + real(b1) * ground.b + real(b2) * ground.c;
        Ray ray = {eye, target - eye};
        RayHit hit;
        if (!s->triangle(&ground, &ray, 0, kInfinity, &hit))
            continue;
        Ray shadow;
        SelfHit start;
        hit.index = 0;
        acne += ShadowRay(&scene, kRobustMethods, &hit, light, &shadow, &start) &&
                s->triangle(&ground, &shadow, 0, 1, &hit);
    }
    return acne;
}

// A ground triangle of radius 1000 around c0 in the plane with normal normalize(0.1, 1, 0.2).
static Triangle GroundAround(vec3 c0) {
    vec3 n = Normalize({0.1, 1, 0.2});
    vec3 e1 = Normalize(Cross(n, {0, 0, 1})), e2 = Cross(n, e1);
    vec3 corner[3];
    for (int k = 0; k < 3; k++) {
        double angle = 2 * M_PI * k / 3;
        corner[k] = c0 + real(1000 * cos(angle)) * e1 + real(1000 * sin(angle)) * e2;
    }
    return {corner[0], corner[1], corner[2], 0};
}

void OffsetRows(Suite *s) {
    // OFF-1: acne at |p| ~ 1e5 in float (the catalogue's exact float triangle, eye and light)
    Triangle ground = {{60944.85546875, 29847.546875, 74289.8359375},
                       {59256.84375, 29941.013671875, 74666.515625},
                       {59798.296875, 30211.44140625, 73043.6484375},
                       0};
    int acne = SelfShadowed(s, ground, {60000.48828125, 30004.87890625, 74000.9765625},
                            {60030.0, 30080.0, 74040.0}, 300, 1);
    Report(s, "OFF-1", acne == 0, std::to_string(acne) + " of 300 points shadowed themselves");
    if (kDouble) { // OFF-2: the same at |p| ~ 1e5, 1e9, 1e12, 1e13 in double
        acne = 0;
        for (double c : {1e5, 1e9, 1e12, 1e13}) {
            vec3 c0 = real(c) * vec3{0.6, 0.3, 0.74};
            vec3 n = Normalize({0.1, 1, 0.2});
            acne +=
                SelfShadowed(s, GroundAround(c0), c0 + real(5) * n, c0 + vec3{30, 80, 40}, 200, 2);
        }
        Report(s, "OFF-2", acne == 0, std::to_string(acne) + " of 800 points shadowed themselves");
    }
    { // OFF-3: a contact shadow between 1e-4-sized objects, and under a sheet 5e-6 above
        Sphere ball = {{0, 1e-4, 0}, 1e-4, 0};
        Triangle ground = {{-1e-3, 0, -1e-3}, {1e-3, 0, -1e-3}, {0, 0, 1e-3}, 0};
        Triangle sheet = {{-1e-4, 5e-6, -1e-4}, {1e-4, 5e-6, -1e-4}, {0, 5e-6, 1e-4}, 0};
        vec3 light = {0, 1e-3, 0};
        Ray up = {{2e-5, -1, 0}, {0, 1, 0}}; // finds P = (2e-5, 0, 0) on the ground
        RayHit p, blocker;
        bool found = s->triangle(&ground, &up, 0, kInfinity, &p);
        Ray shadow;
        SelfHit start;
        Scene scene = OneTriangle(ground);
        p.index = 0;
        found = found && ShadowRay(&scene, kRobustMethods, &p, light, &shadow, &start);
        bool ballShadows = found && s->sphere(&ball, &shadow, 0, 1, &blocker);
        bool sheetShadows = found && s->triangle(&sheet, &shadow, 0, 1, &blocker);
        Report(s, "OFF-3", ballShadows && sheetShadows,
               std::string(ballShadows ? "" : "light leaks past the sphere; ") +
                   (sheetShadows ? "" : "light leaks past the sheet"));
    }
    if (kDouble) { // OFF-4: shadow rays leaving a sphere (RTIOW's scene) with t_min = 0
        Sphere ball = {{0, 0, -1}, 0.5, 0};
        vec3 light = {3, 4, 2};
        int rays = 0;
        acne = 0;
        for (int j = 0; j < 60; j++)
            for (int i = 0; i < 60; i++) {
                Ray ray = {{0, 0, 0}, {real(-0.55 + i / 54.0), real(-0.55 + j / 54.0), -1}};
                RayHit hit, again;
                if (!s->sphere(&ball, &ray, 0, kInfinity, &hit) ||
                    !(Dot(hit.normal, light - hit.point) > 0))
                    continue;
                Ray shadow;
                SelfHit start;
                rays++;
                Scene scene; // (a sphere's ray leaves from its own point alone)
                acne += ShadowRay(&scene, kRobustMethods, &hit, light, &shadow, &start) &&
                        s->sphere(&ball, &shadow, 0, 1, &again);
            }
        Report(s, "OFF-4", acne == 0 && rays > 1000,
               std::to_string(acne) + " of " + std::to_string(rays) +
                   " shadow rays re-hit the sphere");
    }
}
