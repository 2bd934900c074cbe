// path_sampling.h -- the path tracer's random numbers, directions and points on emitters: the
// Monte Carlo half of `shading path`, each formula with its source. Included by path.cpp alone,
// so that these short functions inline into the path loop as they would in one file.
#pragma once
#include "ray.h"

#include <algorithm>

// Which path a random number belongs to: the render's seed, the pixel and the sample in it,
// already hashed (PathKey), since they stay the same along the whole path.
struct PathSample {
    uint64_t key;
};

// The random bits for one decision of one path: SplitMix64's finaliser (as the jitter's hash,
// render.cpp) over the seed, the pixel, the sample, the bounce and the decision, with a word of
// its own so these never repeat the jitter's numbers. The first four words are mixed once a path
// (PathKey), the last once a decision: the same bits as mixing all five every time.
static PathSample PathKey(int seed, int i, int j, int s) {
    uint64_t z = 0x70617468; // "path"
    for (uint64_t word : {(uint64_t)seed, (uint64_t)i, (uint64_t)j, (uint64_t)s})
        z = MixWord(z, word);
    return {z};
}
static uint64_t PathHash(const PathSample *p, int bounce, int dimension) {
    return MixWord(p->key, (uint64_t)bounce * 16 + (uint64_t)dimension);
}

// A random number in [0, 1) from 24 of the bits: exact in float too, and below 1.
static real PathRandom(const PathSample *p, int bounce, int dimension) {
    return real((PathHash(p, bounce, dimension) >> 40) * (1.0 / 16777216.0));
}

// Two unit vectors that make an orthonormal basis with the unit n (Duff et al., "Building an
// Orthonormal Basis, Revisited", JCGT 6(1), 2017: no division by a small number, no branch on
// which axis n is near).
static void Basis(vec3 n, vec3 *t, vec3 *b) {
    real sign = std::copysign(real(1), n.z);
    real a = -1 / (sign + n.z), c = n.x * n.y * a;
    *t = {1 + sign * n.x * n.x * a, sign * c, -sign * n.x};
    *b = {c, sign + n.y * n.y * a, -n.y};
}

// The density (per solid angle) with which the scatter method draws a direction at angle theta
// from the normal: cos(theta) / pi, or 1 / (2 pi) over the hemisphere.
static real ScatterPdf(ScatterMethod method, real cosTheta) {
    return method == SCATTER_COSINE ? cosTheta / kPi : 1 / (2 * kPi);
}

// A random direction on the hemisphere around the unit n. Cosine-weighted: a uniform point on
// the unit disk lifted onto the hemisphere (Malley's method; Ray Tracing in One Weekend's
// normal + random_unit_vector draws the same density). Uniform: cos(theta) uniform in [0, 1)
// (Archimedes: equal heights cut equal areas from a sphere).
static vec3 ScatterDirection(ScatterMethod method, vec3 n, real u, real v) {
    real cosTheta = method == SCATTER_COSINE ? std::sqrt(1 - u) : 1 - u;
    real sinTheta = std::sqrt(std::max(real(0), 1 - cosTheta * cosTheta));
    real phi = 2 * kPi * v;
    vec3 t, b;
    Basis(n, &t, &b);
    return (sinTheta * std::cos(phi)) * t + (sinTheta * std::sin(phi)) * b + cosTheta * n;
}

// Veach's power heuristic (Veach, "Robust Monte Carlo Methods for Light Transport Simulation",
// 1997, §9.2.4, beta = 2): the weight of a sample drawn with density a, when density b could
// also have drawn it.
static real PowerHeuristic(real a, real b) {
    if (!(a > 0))
        return 0;
    real r = b / a; // (as a ratio: a^2 alone can overflow for a tiny, distant emitter)
    return std::isfinite(r) ? 1 / (1 + r * r) : 0;
}

// ---- emitters: the shapes whose material has `emit` (PlanEffects lists them) ---------------

// A point drawn uniformly over the emitter's surface, and the unit normal there. A sphere: the
// height z uniform in [-1, 1] (Archimedes again). A triangle: barycentric coordinates from the
// square root of u, which spreads the points evenly (Shirley & Chiu 1997; pbrt-v4 §A.5.4).
static void SampleEmitter(const Scene *scene, const Emitter *e, real u, real v, vec3 *p, vec3 *n) {
    if (e->shape == SHAPE_SPHERE) {
        const Sphere *s = &scene->spheres[e->index];
        real z = 1 - 2 * u, r = std::sqrt(std::max(real(0), 1 - z * z)), phi = 2 * kPi * v;
        *n = {r * std::cos(phi), r * std::sin(phi), z};
        *p = s->center + s->radius * *n;
        return;
    }
    const Triangle *t = &scene->triangles[e->index];
    real root = std::sqrt(u), b0 = 1 - root, b1 = v * root;
    *p = b0 * t->a + b1 * t->b + (1 - b0 - b1) * t->c;
    *n = e->normal;
}

// The density, per solid angle at the shaded point, with which next-event estimation picks a
// point of an emitter of this area, seen dist2 away (squared) at cosine cosLight to its normal:
// 1 / count for the emitter, 1 / area for the point, times dist2 / cosLight from area to solid
// angle.
static real EmitterPdf(size_t count, real area, real dist2, real cosLight) {
    return dist2 / ((real)count * area * cosLight);
}
