// blur.cpp -- Ray Tracing in One Weekend's two blurs beyond the handouts, and the random numbers
// they draw for each pixel sample outside path tracing: defocus (a camera's thin lens, whose ray
// geometry is camera.cpp's GetLensRay) and fuzzy reflection (a mirror's `fuzz`, FuzzReflect in
// render.h). Neither costs anything in a scene without it: the render asks here only when the
// scene has a lens or a fuzzy mirror (Effects). The numbers come from a hash of the pixel, the
// sample and the seed, so the image never depends on the thread count.
#include "ray.h"
#include "render.h"

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

// The key of sample s of pixel (i, j) under the render's seed, with a word of its own for each
// use ("lens", "fuzz"), so that neither repeats the other's numbers or the path tracer's.
static uint64_t SampleKey(uint64_t use, const RenderSettings *settings, int i, int j, int s) {
    uint64_t z = use;
    for (uint64_t word : {(uint64_t)settings->path.seed, (uint64_t)i, (uint64_t)j, (uint64_t)s})
        z = MixWord(z, word);
    return z;
}

void GetSampleRay(const RenderSettings *settings, vec2 position, int i, int j, int s, Ray *ray,
                  RayStats *stats) {
    const Camera *camera = &settings->camera;
    if (!settings->effects.defocus) {
        GetCameraRay(camera, settings->width, settings->height, position, ray);
        return;
    }
    vec2 lens = HashDiskPoint(SampleKey(0x6c656e73, settings, i, j, s)); // "lens"
    GetLensRay(camera, settings->width, settings->height, position, lens, ray);
    stats->defocus++;
}

void StartSample(const RenderSettings *settings, int i, int j, int s, TraceLog *log) {
    if (settings->effects.fuzz)
        log->sample = SampleKey(0x66757a7a, settings, i, j, s), log->draws = 0; // "fuzz"
}

// Each fuzzy reflection of the sample draws the next point: a chain that meets two fuzzy mirrors,
// or glass that splits it, takes a fresh point at each, in the order the rays are traced.
bool FuzzyMirror(real fuzz, vec3 d, vec3 n, TraceLog *log, vec3 *dir) {
    log->stats.fuzz++;
    vec3 unit = RandomUnitVector(HashDiskPoint(MixWord(log->sample, log->draws++)));
    return FuzzReflect(SafeNormalize(d), n, fuzz, unit, dir);
}
