// blur.cpp -- the random numbers of Ray Tracing in One Weekend's two blurs beyond the handouts,
// outside path tracing: the point of a camera's thin lens each eye ray starts from (defocus; the
// ray itself is camera.cpp's GetLensRay), and a fuzzy mirror's direction under `floor` and
// `phong` (fuzz; the direction itself is render.h's FuzzReflect). Neither costs anything in a
// scene without it: the camera asks here only when it has a lens, the shading only when a mirror
// has fuzz. The numbers are hashes of what they belong to (the sample's place on the screen, the
// ray that meets the mirror) and the seed, so the image never depends on the thread count.
#include "ray.h"
#include "render.h"

#include <cstring>

// A uniform point of the unit disk from the hash `key`: points of the square [-1, 1)^2, from
// pairs of 24-bit numbers of the hashes of (key, try), until one falls inside (the book's
// random_in_unit_disk; each try falls inside with probability pi/4). Square roots, sines and
// cosines are not needed, so every processor draws the same point. Each try is a hash of its
// own, so the tries never run out; after 64 misses in a row, a chance of (1 - pi/4)^64, below
// 1e-42, the centre is taken.
static vec2 HashDiskPoint(uint64_t key) {
    for (uint64_t k = 0; k < 64; k++) {
        uint64_t bits = MixWord(key, k);
        real x = real((bits >> 40) * (2.0 / 16777216.0)) - 1; // exact: 24 bits of [0, 1), doubled
        real y = real((bits >> 16 & 0xffffff) * (2.0 / 16777216.0)) - 1;
        if (x * x + y * y < 1)
            return {x, y};
    }
    return {0, 0};
}

// The bits of a number, as a word to hash (a float's 32 bits, a double's 64).
static uint64_t Bits(real x) {
    uint64_t word = 0;
    memcpy(&word, &x, sizeof x);
    return word;
}

// Each use has a word of its own ("lens", "fuzz") mixed in first, so that neither repeats the
// other's numbers or the path tracer's. A sample's place on the screen names it: samples of one
// pixel lie at different places, and so do those of different pixels (the grid's, the jitter's),
// and where two coincide (an adaptive pixel's corner, shared with its neighbour) they are one ray.
void GetLensCameraRay(const Camera *camera, int width, int height, vec2 screenCoord, Ray *ray) {
    uint64_t key = MixWord(0x6c656e73, (uint64_t)camera->seed); // "lens"
    key = MixWord(MixWord(key, Bits(screenCoord.x)), Bits(screenCoord.y));
    GetLensRay(camera, width, height, screenCoord, HashDiskPoint(key), ray);
}

// A ray names its fuzzy reflection: the samples of a pixel send different rays, and so does
// every branch of a sample's tree (a chain that meets two fuzzy mirrors, glass that splits it),
// so each draws a point of its own; a ray that two samples share is the same ray, which reflects
// the same way.
bool FuzzyMirror(real fuzz, const Ray *ray, vec3 n, int seed, vec3 *dir) {
    uint64_t key = MixWord(0x66757a7a, (uint64_t)seed); // "fuzz"
    for (real x : {ray->origin.x, ray->origin.y, ray->origin.z, ray->dir.x, ray->dir.y, ray->dir.z})
        key = MixWord(key, Bits(x));
    vec3 unit = RandomUnitVector(HashDiskPoint(key));
    return FuzzReflect(SafeNormalize(ray->dir), n, fuzz, unit, dir);
}
