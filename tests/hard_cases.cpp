// tests/hard_cases.cpp -- rt's numerical hard cases for spheres (SPH), triangles (TRI) and
// self-intersection (OFF), each with its exact expected result; their families are described in
// docs/robustness.md. The refraction (REF) and Phong (PH) cases test shading, not intersection,
// and live in test_effects.cpp.
//
// Expected values were computed with 50-digit arithmetic; where a sweep needs many expected
// values they are computed here in long double from the same inputs. The self-intersection (OFF)
// cases are in hard_cases_offset.cpp.

#include "../app/app.h"
#include "hard_cases_suite.h"

#include <cstdint>

static bool HitsAny(const Suite *s, const std::vector<Triangle> &tris, const Ray *ray, real tMax) {
    RayHit hit;
    for (const Triangle &t : tris)
        if (s->triangle(&t, ray, 0, tMax, &hit))
            return true;
    return false;
}

// The entry root of |o + t d - c| = r for a ray from outside, in long double from the inputs.
static long double ExactEntry(vec3 o, vec3 d, vec3 c, real r) {
    long double fx = (long double)o.x - c.x, fy = (long double)o.y - c.y,
                fz = (long double)o.z - c.z;
    long double a = (long double)d.x * d.x + (long double)d.y * d.y + (long double)d.z * d.z;
    long double b = fx * d.x + fy * d.y + fz * d.z;
    long double px = fx - b / a * d.x, py = fy - b / a * d.y, pz = fz - b / a * d.z;
    long double disc = a * ((long double)r * r - (px * px + py * py + pz * pz));
    return disc < 0 ? -1 : (-b - sqrtl(disc)) / a;
}

// One sphere row: hit or miss as expected, and t within tolerance of the expected value.
static std::string CheckSphere(const Suite *s, Sphere sphere, Ray ray, bool expectHit, double t,
                               double tolerance) {
    RayHit hit;
    bool got = s->sphere(&sphere, &ray, 0, kInfinity, &hit);
    char text[160];
    if (got != expectHit)
        snprintf(text, sizeof text, "expected %s, got %s (t=%.17g)", expectHit ? "hit" : "miss",
                 got ? "hit" : "miss", got ? (double)hit.t : 0.0);
    else if (got && !(std::fabs(hit.t - t) <= tolerance))
        snprintf(text, sizeof text, "t=%.17g, expected %.17g within %.3g", (double)hit.t, t,
                 tolerance);
    else
        return "";
    return text;
}

static void SphereRows(Suite *s) {
    Sphere unit = {{0, 0, 0}, 1, 0};
    std::string why;
    if (kDouble) { // SPH-1: r = 1 at distance 1e9, the textbook c = f.f - r^2 loses r entirely
        const double ys[] = {0.5, 0.99, 1.01, 2.0};
        const double t0[] = {999999999.13397459622, 999999999.8589326402, 0, 0};
        for (int k = 0; k < 4; k++)
            why +=
                CheckSphere(s, unit, {{real(-1e9), real(ys[k]), 0}, {1, 0, 0}}, k < 2, t0[k], 1e-6);
        Report(s, "SPH-1", why.empty(), why);
    }
    if (kDouble) { // SPH-2: oblique rays at distance 1e8, y in [-1.2, 1.2]
        vec3 d = {0.3333333333333333, 0.6666666666666666, 0.6666666666666666};
        vec3 m = Normalize(Cross(d, {0, 0, 1}));
        int wrong = 0;
        for (int k = 0; k <= 100; k++) {
            real y = real(-1.2 + 2.4 * k / 100);
            vec3 o = real(-1e8) * d + y * m;
            long double exact = ExactEntry(o, d, unit.center, 1);
            wrong += !CheckSphere(s, unit, {o, d}, exact > 0, (double)exact, 6e-8).empty();
        }
        why = CheckSphere(s, unit,
                          {{-33333333.247468323, -66666666.70959917, -66666666.666666664}, d}, true,
                          99999999.00461866646, 6e-8);
        Report(s, "SPH-2", wrong == 0 && why.empty(),
               std::to_string(wrong) + " of 101 rays wrong; worst case: " + why);
    }
    { // SPH-3: RTG Fig. 7-3, unit sphere at distance 4100 (the float build's edge)
        const double ys[] = {0, 0.5, 0.9, 1.1};
        why.clear();
        for (int k = 0; k < 4; k++)
            why += CheckSphere(s, unit, {{-4100, real(ys[k]), 0}, {1, 0, 0}}, k < 3,
                               4100 - std::sqrt(1 - ys[k] * ys[k]), kDouble ? 1e-9 : 2e-3);
        Report(s, "SPH-3", why.empty(), why);
    }
    if (kDouble) { // SPH-4: grazing rays 1e-5 inside and outside the silhouette at 1e6
        vec3 d = {0.3333333333333333, 0.6666666666666666, 0.6666666666666666};
        why =
            CheckSphere(s, unit, {{-333332.43891508656, -666667.11387579, -666666.6666666666}, d},
                        true, 999999.99552788441295, 1e-9) +
            CheckSphere(s, unit, {{-333332.43889719807, -666667.1138847342, -666666.6666666666}, d},
                        false, 0, 0);
        Report(s, "SPH-4", why.empty(), why);
    }
    if (kDouble) { // SPH-5: a huge sphere 1.2e-10 away: the near root needs c / q
        why = CheckSphere(s, {{0, 0, 0}, 1e6, 0}, {{0, 1e6, 1.0 / 64}, {3, -4, 0}}, true,
                          3.051757812500000291e-11, 3.051757812500000291e-11 * 1e-12);
        Report(s, "SPH-5", why.empty(), why);
    }
    { // SPH-6: origin inside: the far root, seen from inside (front face false, normal flipped)
        RayHit hit;
        Ray ray = {{0.5, 0, 0}, {0, 1, 0}};
        bool got = s->sphere(&unit, &ray, 0, kInfinity, &hit);
        bool ok = got && std::fabs(hit.t - 0.86602540378443864676) <= 8 * kUnitRoundoff &&
                  !hit.frontFace && std::fabs(hit.normal.x + real(0.5)) <= 8 * kUnitRoundoff &&
                  std::fabs(hit.normal.y + real(0.86602540378443865)) <= 8 * kUnitRoundoff;
        Report(s, "SPH-6", ok, got ? "t=" + std::to_string(hit.t) : "miss");
    }
    why = CheckSphere(s, {{0, 0, 5}, 1, 0}, {{0, 0, 0}, {0, 0, -1}}, false, 0, 0); // SPH-7
    Report(s, "SPH-7", why.empty(), why);
    { // SPH-8: |d| = 1e-3: t = 4 / d exactly, 3999.99999999999992 in double
        real dz = real(-0.001);
        why = CheckSphere(s, {{0, 0, -5}, 1, 0}, {{0, 0, 0}, {0, 0, dz}}, true,
                          (double)(4 / -(long double)dz), 4 * 4000 * kUnitRoundoff * 2);
        Report(s, "SPH-8", why.empty(), why);
    }
    { // SPH-9: |d| = 1e3: the front face at t = 5e-4, not the back face at 2.5e-3
        RayHit hit;
        Sphere sp = {{0, 0, -1.5}, 1, 0};
        Ray ray = {{0, 0, 0}, {0, 0, -1000}};
        bool ok = s->sphere(&sp, &ray, 0, kInfinity, &hit) &&
                  std::fabs(hit.t - 5e-4) <= 5e-4 * 4 * kUnitRoundoff && hit.frontFace;
        Report(s, "SPH-9", ok, ok ? "" : "not the front face at t = 5e-4");
    }
    { // SPH-10: a zero direction is refused where rays are made; NaN and infinity miss
        Ray ray;
        bool blank;
        std::string error;
        bool refused = !ParseProbeLine("0 0 5 0 0 0", &ray, &blank, &error);
        RayHit hit;
        Ray nanDir = {{0, 0, 5}, {real(NAN), 0, -1}},
            infOrigin = {{real(INFINITY), 0, 5}, {0, 0, -1}};
        bool miss = !s->sphere(&unit, &nanDir, 0, kInfinity, &hit) &&
                    !s->sphere(&unit, &infOrigin, 0, kInfinity, &hit);
        Report(s, "SPH-10", refused && miss,
               refused ? "a NaN or infinite ray hit" : "zero accepted");
    }
}

static void SingleTriangleRows(Suite *s) {
    Triangle unit = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 0};
    RayHit hit;
    Ray parallel = {{0.25, 0.25, 1}, {1, 0, 0}}, inPlane = {{-1, 0.25, 0}, {1, 0, 0}};
    Report(s, "TRI-1", !s->triangle(&unit, &parallel, 0, kInfinity, &hit), "parallel ray hit");
    Report(s, "TRI-2", !s->triangle(&unit, &inPlane, 0, kInfinity, &hit), "in-plane ray hit");
    Triangle collinear = {{0, 0, 0}, {1, 1, 1}, {2, 2, 2}, 0};
    Ray down = {{1, 1, 5}, {0, 0, -1}};
    Report(s, "TRI-3", !s->triangle(&collinear, &down, 0, kInfinity, &hit), "degenerate hit");
    Triangle repeated = {{0, 0, 0}, {0, 0, 0}, {1, 0, 0}, 0};
    Triangle point = {{0.3, 0.3, 0}, {0.3, 0.3, 0}, {0.3, 0.3, 0}, 0};
    Ray r1 = {{0.5, 0, 1}, {0, 0, -1}}, r2 = {{0.3, 0.3, 1}, {0, 0, -1}};
    Report(s, "TRI-4",
           !s->triangle(&repeated, &r1, 0, kInfinity, &hit) &&
               !s->triangle(&point, &r2, 0, kInfinity, &hit),
           "a zero-area triangle was hit");
    // TRI-5: half a millimetre in a metre scene; a fixed determinant epsilon rejects it
    Triangle small = {{0, 0, 0}, {5e-4, 0, 0}, {0, 5e-4, 0}, 0};
    Ray ray = {{1e-4, 1e-4, 1}, {0, 0, -1}};
    bool ok =
        s->triangle(&small, &ray, 0, kInfinity, &hit) && std::fabs(hit.t - 1) <= 4 * kUnitRoundoff;
    Report(s, "TRI-5", ok, "the small triangle was missed");
}

// Which side of the plane through the edge B->C and the direction d the point x lies on, in
// long double; 0 when too close to call (the edge is then nearly a silhouette).
static int Side(vec3 b, vec3 c, vec3 d, vec3 x) {
    long double ex = (long double)c.x - b.x, ey = (long double)c.y - b.y,
                ez = (long double)c.z - b.z;
    long double xx = (long double)x.x - b.x, xy = (long double)x.y - b.y,
                xz = (long double)x.z - b.z;
    long double det =
        ex * (d.y * xz - d.z * xy) - ey * (d.x * xz - d.z * xx) + ez * (d.x * xy - d.y * xx);
    return det > 1e-9L ? 1 : det < -1e-9L ? -1 : 0;
}

// True if y - x is exact for every coordinate (Sterbenz: x and y within a factor of 2).
static bool SterbenzExact(vec3 x, vec3 y) {
    real xs[3] = {x.x, x.y, x.z}, ys[3] = {y.x, y.y, y.z};
    for (int k = 0; k < 3; k++)
        if (!(xs[k] > 0 && ys[k] > 0 && xs[k] <= 2 * ys[k] && ys[k] <= 2 * xs[k]))
            return false;
    return true;
}

// TRI-6 (double) / TRI-7 (float): rays exactly through the shared edge of two folded triangles.
static void SharedEdgeRow(Suite *s) {
    vec3 A = {0.1, 0.2, 0.3}, B = {1.75, 0.25, 0.125}, C = {0.375, 1.875, 0.75},
         D = {1.9, 1.6, 0.2};
    std::vector<Triangle> pair = {{A, B, C, 0}, {B, D, C, 0}};
    const char *id = kDouble ? "TRI-6" : "TRI-7";
    // The catalogue's ray, exact in double: through P = B + 0.890625 (C - B) at t = 1
    Ray given = {{0.3860834547576302, 1.919954052685838, 0.8812225435609884},
                 {0.13930717024236983, -0.22268842768583808, -0.1995819185609884}};
    bool givenHits = !kDouble || HitsAny(s, pair, &given, kInfinity);
    // The sweep: points P exactly on BC (B + k/4096 (C - B) is exact: few bits), origins O at
    // random around the catalogue's, kept only where d = P - O is exact, so every ray passes
    // through P; rays for which the edge is a silhouette are left out
    SweepRng rng = {6};
    int rays = 0, misses = 0;
    for (int k = 1; k < 4096; k++) {
        vec3 p = B + (real(k) / 4096) * (C - B);
        for (int j = 0; j < 6; j++) {
            vec3 wobble = {real(rng.Next() * 0.1 - 0.05), real(rng.Next() * 0.1 - 0.05),
                           real(rng.Next() * 0.1 - 0.05)};
            vec3 o = p - (given.dir + wobble);
            if (!SterbenzExact(o, p))
                continue;
            vec3 d = p - o;
            if (Side(B, C, d, A) * Side(B, C, d, D) >= 0)
                continue;
            Ray ray = {o, d};
            rays++;
            misses += !HitsAny(s, pair, &ray, kInfinity);
        }
    }
    Report(s, id, givenHits && misses == 0 && rays > 4000,
           std::to_string(misses) + " of " + std::to_string(rays) + " edge rays slipped through" +
               (givenHits ? "" : "; the catalogue's ray slipped through"));
}

// TRI-8: the catalogue's 7-triangle fan, the given ray and a sweep of rays exactly through V.
static void FanRow(Suite *s) {
    vec3 V = {1.1, 1.3, 0.7};
    const vec3 ring[7] = {{0.9548786822178472, 1.765511529676899, 0.5893708046533608},
                          {0.6427316614941732, 1.4997803382335817, 0.7315195662310908},
                          {0.6749170262396122, 1.0836104773241542, 0.8499334515548314},
                          {1.027198540339056, 0.8303863405314802, 0.8554443897727447},
                          {1.434301038442331, 0.9307908676914814, 0.7439025320040894},
                          {1.5896680361000994, 1.3092174019735736, 0.599301172187908},
                          {1.3763050151668816, 1.6807030445688298, 0.5305280835959747}};
    std::vector<Triangle> fan;
    for (int k = 0; k < 7; k++)
        fan.push_back({V, ring[k], ring[(k + 1) % 7], 0});
    Ray given = {{1.1505510757821193, 1.5425210625086652, 1.1727928546539865},
                 {-0.05055107578211926, -0.24252106250866512, -0.47279285465398657}};
    bool givenHits = !kDouble || HitsAny(s, fan, &given, kInfinity);
    SweepRng rng = {8};
    int misses = 0;
    for (int k = 0; k < 20000; k++) {
        vec3 toward = {real(rng.Next() * 0.6 - 0.3), real(rng.Next() * 0.6 - 0.3),
                       real(-0.3 - 0.2 * rng.Next())};
        vec3 o = V - toward;
        Ray ray = {o, V - o}; // exact (Sterbenz): the ray passes through V itself
        misses += !HitsAny(s, fan, &ray, kInfinity);
    }
    Report(s, "TRI-8", givenHits && misses == 0,
           std::to_string(misses) + " of 20000 rays through the shared vertex found nothing" +
               (givenHits ? "" : "; the catalogue's ray found nothing"));
}

static void FarSmallTriangleRows(Suite *s) {
    RayHit hit;
    if (kDouble) { // TRI-9: size 1e-8 at distance 1e6, seen at 88 degrees
        Triangle t = {{507624.3814020193, 495147.61050366884, 705086.0452588282},
                      {507624.38140200934, 495147.61050366866, 705086.0452588276},
                      {507624.38140201475, 495147.6105036634, 705086.0452588211},
                      0};
        Ray ray = {{0, 0, 0}, {507624.38140201446, 495147.61050366703, 705086.0452588256}};
        bool ok = s->triangle(&t, &ray, 0, kInfinity, &hit) &&
                  std::fabs(hit.t - 1.0000000000000014288) < 1e-12;
        Report(s, "TRI-9", ok, "the small far triangle was missed");
    }
    // TRI-10: size 0.01 at distance 1e4 (exact in float, so it runs in both builds)
    Triangle t = {{6086.27001953125, 6134.7255859375, 5032.140625},
                  {6086.2685546875, 6134.72998046875, 5032.14990234375},
                  {6086.2626953125, 6134.72265625, 5032.146484375},
                  0};
    Ray ray = {{0, 0, 0}, {6086.26708984375, 6134.72607421875, 5032.1455078125}};
    bool ok = s->triangle(&t, &ray, 0, kInfinity, &hit) &&
              std::fabs(hit.t - 1.0000000419568469042) < 1e-6;
    Report(s, "TRI-10", ok, "the small far triangle was missed");
}

// TRI-11: a closed UV sphere (r = 2 at (0.3, 0.2, 0.1), 24 x 12 segments, 266 vertices, 528
// triangles); from 3 interior points, rays at every vertex and every edge midpoint.
static void ClosedMeshRow(Suite *s) {
    const int segments = 24, rings = 12;
    vec3 centre = {0.3, 0.2, 0.1};
    std::vector<vec3> v = {centre + vec3{0, 0, 2}, centre + vec3{0, 0, -2}};
    for (int i = 1; i < rings; i++)
        for (int j = 0; j < segments; j++) {
            double theta = M_PI * i / rings, phi = 2 * M_PI * j / segments;
            v.push_back({real(0.3 + 2 * sin(theta) * cos(phi)),
                         real(0.2 + 2 * sin(theta) * sin(phi)), real(0.1 + 2 * cos(theta))});
        }
    auto at = [](int i, int j) { return 2 + (i - 1) * segments + (j % segments); };
    std::vector<int> idx;
    for (int j = 0; j < segments; j++) {
        idx.insert(idx.end(), {0, at(1, j), at(1, j + 1)});
        idx.insert(idx.end(), {1, at(rings - 1, j + 1), at(rings - 1, j)});
        for (int i = 1; i < rings - 1; i++) {
            idx.insert(idx.end(), {at(i, j), at(i + 1, j), at(i + 1, j + 1)});
            idx.insert(idx.end(), {at(i, j), at(i + 1, j + 1), at(i, j + 1)});
        }
    }
    std::vector<Triangle> mesh;
    std::vector<vec3> targets(v);
    for (size_t k = 0; k < idx.size(); k += 3) {
        mesh.push_back({v[idx[k]], v[idx[k + 1]], v[idx[k + 2]], 0});
        for (int e = 0; e < 3; e++) { // each edge once: from the lower index to the higher
            int a = idx[k + e], b = idx[k + (e + 1) % 3];
            if (a < b)
                targets.push_back(real(0.5) * (v[a] + v[b]));
        }
    }
    SweepRng rng = {4};
    int escapes = 0, rays = 0;
    for (int o = 0; o < 3; o++) {
        vec3 origin =
            centre + vec3{real(rng.Next() - 0.5), real(rng.Next() - 0.5), real(rng.Next() - 0.5)};
        for (vec3 target : targets) {
            Ray ray = {origin, target - origin};
            rays++;
            escapes += !HitsAny(s, mesh, &ray, kInfinity);
        }
    }
    Report(s, "TRI-11", escapes == 0 && mesh.size() == 528 && rays == 3 * (266 + 792),
           std::to_string(escapes) + " of " + std::to_string(rays) + " rays escaped the mesh");
}

void RunHardCases(SphereRoutine sphere, TriangleRoutine triangle,
                  std::vector<HardCaseResult> *results) {
    Suite s = {sphere, triangle, results};
    SphereRows(&s);
    SingleTriangleRows(&s);
    SharedEdgeRow(&s);
    FanRow(&s);
    FarSmallTriangleRows(&s);
    ClosedMeshRow(&s);
    OffsetRows(&s);
}
