// path_sampling.h -- the path tracer's random numbers, directions and points on emitters: the
// Monte Carlo half of `shading path`, each formula with its source (included through path.h by the
// two estimators' files; its functions are inline, each file keeping those it uses).
#pragma once
#include "ray.h"
#include "render.h"

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
static inline PathSample PathKey(int seed, int i, int j, int s) {
    uint64_t z = 0x70617468; // "path"
    for (uint64_t word : {(uint64_t)seed, (uint64_t)i, (uint64_t)j, (uint64_t)s})
        z = MixWord(z, word);
    return {z};
}
// The hashes each bounce may take: its decisions (path.cpp) and the tries of its disk points.
const int kDimensionsPerBounce = 16;
static inline uint64_t PathHash(const PathSample *p, int bounce, int dimension) {
    return MixWord(p->key, (uint64_t)bounce * kDimensionsPerBounce + (uint64_t)dimension);
}

// A random number in [0, 1) from 24 of the bits: exact in float too, and below 1.
static inline real PathRandom(const PathSample *p, int bounce, int dimension) {
    return real((PathHash(p, bounce, dimension) >> 40) * (1.0 / 16777216.0));
}

// Two such numbers from one hash: its top 24 bits and the 24 below them. Every bit of the
// finaliser's output depends on every bit of its input, so the two are as independent as two
// hashes would be, for one hash's work.
static inline vec2 PathRandomPair(const PathSample *p, int bounce, int dimension) {
    uint64_t bits = PathHash(p, bounce, dimension);
    return {real((bits >> 40) * (1.0 / 16777216.0)),
            real((bits >> 16 & 0xffffff) * (1.0 / 16777216.0))};
}

// Two unit vectors that make an orthonormal basis with the unit n (Duff et al., "Building an
// Orthonormal Basis, Revisited", JCGT 6(1), 2017: no division by a small number, no branch on
// which axis n is near).
static inline void Basis(vec3 n, vec3 *t, vec3 *b) {
    real sign = std::copysign(real(1), n.z);
    real a = -1 / (sign + n.z), c = n.x * n.y * a;
    *t = {1 + sign * n.x * n.x * a, sign * c, -sign * n.x};
    *b = {c, sign + n.y * n.y * a, -n.y};
}

// The density (per solid angle) with which the scatter method draws a direction at angle theta
// from the normal: cos(theta) / pi, or 1 / (2 pi) over the hemisphere.
static inline real ScatterPdf(ScatterMethod method, real cosTheta) {
    return method == SCATTER_COSINE ? cosTheta / kPi : 1 / (2 * kPi);
}

// A uniform point (x, y) of the unit disk, from the hashes [first, first + kDiskDimensions) of
// this bounce, a pair of numbers from each (PathRandomPair): points of the square [-1, 1)^2
// until one falls inside (Ray Tracing in One Weekend's random_in_unit_disk; each try falls
// inside with probability pi/4). The directions below are made from it with square roots alone:
// no sine or cosine, which cost more than the tries. A path's numbers are keyed by their use, so
// the tries are bounded: if all kDiskTries miss (a chance of (1 - pi/4)^5, about 1 in 2,200),
// one more pair gives the point by radius and angle, r = sqrt(u), phi = 2 pi v, which is
// uniform too; either way the point is uniform.
const int kDiskTries = 5, kDiskDimensions = kDiskTries + 1;
static inline vec2 DiskPoint(const PathSample *p, int bounce, int first) {
    for (int k = 0; k < kDiskTries; k++) {
        vec2 u = PathRandomPair(p, bounce, first + k);
        real x = 2 * u.x - 1, y = 2 * u.y - 1; // exact: 24 bits of [0, 1)
        if (x * x + y * y < 1)
            return {x, y};
    }
    vec2 u = PathRandomPair(p, bounce, first + kDiskTries);
    real r = std::sqrt(u.x), phi = 2 * kPi * u.y;
    return {r * std::cos(phi), r * std::sin(phi)};
}

// A random direction on the hemisphere around the unit n, from a uniform point (x, y) of the
// unit disk, where r^2 = x^2 + y^2 is uniform in [0, 1) and (x, y) / r a uniform direction
// around n:
//   cosine-weighted: (x, y) lifted straight up onto the hemisphere, cos(theta) = sqrt(1 - r^2)
//     (Malley's method; Ray Tracing in One Weekend's normal + random_unit_vector draws the same
//     density);
//   uniform: cos(theta) = 1 - r^2, uniform in (0, 1] (Archimedes: equal heights cut equal areas
//     from a sphere), so sin(theta) = r sqrt(2 - r^2), and the tangent part is (x, y) times
//     sqrt(2 - r^2).
static inline vec3 ScatterDirection(ScatterMethod method, vec3 n, vec2 disk) {
    // (the max: DiskPoint's last resort, by angle, may round r^2 a hair above 1)
    real x = disk.x, y = disk.y, r2 = x * x + y * y;
    real cosTheta = std::sqrt(std::max(real(0), 1 - r2));
    if (method != SCATTER_COSINE) {
        real stretch = std::sqrt(2 - r2);
        x *= stretch, y *= stretch, cosTheta = 1 - r2;
    }
    vec3 t, b;
    Basis(n, &t, &b);
    return x * t + y * b + cosTheta * n;
}

// Veach's power heuristic (Veach, "Robust Monte Carlo Methods for Light Transport Simulation",
// 1997, §9.2.4, beta = 2): the weight of a sample drawn with density a, when density b could
// also have drawn it.
static inline real PowerHeuristic(real a, real b) {
    if (!(a > 0))
        return 0;
    real r = b / a; // (as a ratio: a^2 alone can overflow for a tiny, distant emitter)
    return std::isfinite(r) ? 1 / (1 + r * r) : 0;
}

// ---- emitters: the shapes whose material has `emit` (PlanEffects lists them) ---------------

// A point drawn uniformly over an emitting sphere, and the unit normal there: a random unit
// vector from the centre (RandomUnitVector, render.h).
static inline void SampleSphere(const Sphere *s, vec2 disk, vec3 *p, vec3 *n) {
    *n = RandomUnitVector(disk);
    *p = s->center + s->radius * *n;
}

// The cone of directions in which an emitting sphere is seen from a point x outside it: its axis
// (the unit vector toward the centre) and its half-angle thetaMax, sin thetaMax = r / d at a
// distance d from the centre. Every direction in the cone meets the sphere on the cap x can see,
// so a direction drawn uniformly in it is never wasted on the far side (pbrt-v4's
// Sphere::Sample(ctx), after Shirley, Wang & Zimmerman, "Monte Carlo Techniques for Direct
// Lighting Calculations", 1996). The cone's solid angle is 2 pi (1 - cos thetaMax), kept as
// sin^2 / (1 + cos): 1 - cos alone would cancel to 0 for a small or distant sphere.
struct SphereCone {
    vec3 axis;
    real sinMax, oneMinusCos;
};

// false where x is not outside the sphere (then no cone: every point of it may face x).
static inline bool ConeOfSphere(const Sphere *s, vec3 x, SphereCone *cone) {
    vec3 toCentre = s->center - x;
    real d = SafeLength(toCentre);
    if (!(d > s->radius))
        return false;
    real sinMax = s->radius / d, cosMax = std::sqrt((1 - sinMax) * (1 + sinMax));
    *cone = {(1 / d) * toCentre, sinMax, sinMax * sinMax / (1 + cosMax)};
    return cone->oneMinusCos > 0; // (a sphere so far that its cone underflows is not sampled)
}

// A direction drawn uniformly in the cone, from two uniform numbers (u, v), and the point where
// it first meets the sphere, with the unit normal there. cos theta is uniform in [cos thetaMax,
// 1] (Archimedes), drawn as 1 - cos theta = u (1 - cos thetaMax), and sin^2 theta = h (2 - h)
// from that h, so neither cancels near the axis. The point is named by the angle alpha at the
// centre between it and x's side: cos alpha = sin^2 theta / sin thetaMax + cos theta
// sqrt(1 - sin^2 theta / sin^2 thetaMax) (pbrt-v4, §6.2.4), found from the triangle x, centre,
// point by the law of sines, with no ray to cast.
static inline vec3 SampleSphereCone(const Sphere *s, const SphereCone *cone, vec2 uv, vec3 *n) {
    real h = uv.x * cone->oneMinusCos, cosTheta = 1 - h, sin2Theta = h * (2 - h);
    real ratio = sin2Theta / (cone->sinMax * cone->sinMax); // (in [0, 1] but for rounding)
    real cosAlpha = sin2Theta / cone->sinMax + cosTheta * std::sqrt(std::max(real(0), 1 - ratio));
    cosAlpha = std::min(real(1), cosAlpha);
    real sinAlpha = std::sqrt((1 - cosAlpha) * (1 + cosAlpha)), phi = 2 * kPi * uv.y;
    vec3 t, b;
    Basis(cone->axis, &t, &b);
    *n = (sinAlpha * std::cos(phi)) * t + (sinAlpha * std::sin(phi)) * b - cosAlpha * cone->axis;
    return s->center + s->radius * *n;
}

// The density, per solid angle, of drawing a direction in the cone of one of `count` emitters:
// 1 / count for the emitter, 1 / (2 pi (1 - cos thetaMax)) for the direction.
static inline real ConePdf(size_t count, const SphereCone *cone) {
    return 1 / ((real)count * 2 * kPi * cone->oneMinusCos);
}

// A point drawn uniformly over an emitting triangle, from two uniform numbers (u, v):
// barycentric coordinates from the square root of u, which spreads the points evenly (Shirley &
// Chiu 1997; pbrt-v4 §A.5.4). Its normal is the emitter's.
static inline vec3 SampleTriangle(const Triangle *t, vec2 uv) {
    real root = std::sqrt(uv.x), b0 = 1 - root, b1 = uv.y * root;
    return b0 * t->a + b1 * t->b + (1 - b0 - b1) * t->c;
}

// The density, per solid angle at the shaded point, with which next-event estimation picks a
// point of an emitter whose area is sqrtArea^2 (EmitterSqrtArea), seen `distance`
// away at cosine cosLight to its normal: 1 / count for the emitter, 1 / area for the point,
// times distance^2 / cosLight from area to solid angle. Written as (distance / sqrtArea)^2, a ratio
// of lengths squared: a squared distance alone overflows from 1.3e154 (float 1.8e19) and leaves
// the normal numbers below 1.5e-154 (float 1.1e-19), while the ratio is the same at every scale.
static inline real EmitterPdf(size_t count, real sqrtArea, real distance, real cosLight) {
    real ratio = distance / sqrtArea;
    return ratio * ratio / ((real)count * cosLight);
}
