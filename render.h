// render.h -- how a render lights and samples what the rays hit: the render's settings, the
// effects a scene calls for, chains and trees of rays; lighting, mirrors and glass (shade.cpp);
// the path tracer of `shading path` (path.cpp, path_full.cpp); the render loop on all cores and
// its sampling (render.cpp). The scene, the cameras and the nearest hit are ray.h's.
#pragma once
#include "ray.h"

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

// ---- render plumbing: effects, settings, chains and trees of rays (shade.cpp, render.cpp) --

// A shape whose material emits (`emit`), by kind and place in its array.
struct Emitter {
    ShapeKind shape;
    int index;
    real sqrtArea; // EmitterSqrtArea, once per render (every light sample divides by it)
    vec3 normal;   // a triangle's unit normal, once per render (every light sample uses it)
    color emit;    // its material's emitted radiance
};

// Which effects a render can need, decided once per render from the scene and the settings
// (PlanEffects); the shading code skips whole paths for the absent ones.
struct Effects {
    bool shadows;                  // lights that can change a surface, and shapes that could
                                   // stand in their way (LightsCanShow)
    bool reflection;               // a material with mirror > 0 or glass, and depth > 1
    bool refraction;               // a glass material, and depth > 1
    bool specular;                 // Phong shading, lights, and a material with ks > 0
    bool antialiasing;             // more than one sample per pixel
    bool indirect;                 // `shading path`: light scattered by diffuse surfaces
    std::vector<Emitter> emitters; // `shading path`: the shapes that emit, for next-event
                                   // estimation (path_full.cpp)
    color lightSum;                // every light's intensity added up
    bool defocus = false;          // a camera with a lens: eye rays start on its disk (blur.cpp)
    bool fuzz = false;             // a mirror with fuzz, and depth > 1
};

// Where a pixel's samples go (--aa).
enum SampleMethod {
    SAMPLES_GRID,    // a regular grid of cell centres
    SAMPLES_JITTER,  // one random point in each grid cell (stratified), seeded by the pixel
    SAMPLES_ADAPTIVE // centre and corners, then the rest jittered only where those five disagree
};

// Adaptive sampling refines a pixel when its first five samples (centre and corners) differ by
// more than this in a channel (0..1), or their rays met different shapes. At edges the shapes
// decide, so a finer contrast would only refine smooth gradients: a sixteenth is a step a viewer
// sees in one.
const real kAdaptiveContrast = real(1) / 16;

// How `shading path` estimates the light a diffuse surface scatters (path.cpp), each choice
// selectable so that `make bench` can compare them. The journal's estimator, as Ray Tracing in
// One Weekend writes it, or rt's, which adds the steps below.
enum Estimator {
    ESTIMATOR_FULL,   // next-event estimation, MIS, cosine sampling, roulette (the default)
    ESTIMATOR_JOURNAL // scatter by normal + a random unit vector, times the reflectance, until a
                      // miss or the depth cap; light only from what a ray hits
};
enum ScatterMethod {
    SCATTER_COSINE, // directions drawn with density cos(theta) / pi (Ray Tracing in One Weekend's
                    // normal + random_unit_vector): the default
    SCATTER_UNIFORM // uniform over the hemisphere, density 1 / (2 pi) (the journal's
                    // random_in_hemisphere)
};
enum LightMethod {
    LIGHTS_MIS, // next-event estimation to point lights and emitting shapes, combined with
                // scattered rays that hit emitters by multiple importance sampling (the default)
    LIGHTS_NEE, // next-event estimation only: a scattered ray that hits an emitter adds nothing
    LIGHTS_NONE // scattered rays only: light arrives when a path happens to hit an emitter
};
// How next-event estimation draws a point on an emitting sphere seen from outside it.
enum SphereSampling {
    SPHERES_CONE, // a direction uniform in the cone the sphere subtends: only the cap that can be
                  // seen (the default)
    SPHERES_AREA  // a point uniform over the whole sphere, half of which faces away
};
// The defaults are all zero, so `{}` asks for them.
struct PathMethods {
    Estimator estimator;
    ScatterMethod scatter;
    LightMethod lights;
    bool noRoulette; // only `depth` ends paths (biased); else Russian roulette does (unbiased)
    int seed;        // mixed into every random number: another seed, another (equally good) noise
    SphereSampling spheres;
};

// How far a render has come, for a progress line: the share of rows done, the rays cast a second
// so far (every kind), and the seconds the rest will likely take. `finished`: the last report, so
// that a line drawn in place can be cleared.
struct RenderProgress {
    double done, raysPerSecond, secondsLeft;
    bool finished;
};
typedef void (*ProgressReport)(const RenderProgress *progress);

// How one render is done; filled from the scene and the command line.
struct RenderSettings {
    int width, height;   // image size in pixels
    int samplesPerPixel; // primary rays per pixel (the most, for adaptive sampling)
    SampleMethod sampling;
    int depth;       // most rays in one chain, primary included
    int threads;     // worker threads; the image never depends on it
    Methods methods; // the numerical methods (kRobustMethods, or as --methods and co. choose)
    ProgressReport progress; // called every half second of a render that runs that long, and
                             // then once at its end; nullptr: none (Render itself never prints)
    Effects effects;         // filled by PlanRender
    Camera camera;           // the scene's camera for this image size, filled by PlanRender
    PathMethods path;        // how `shading path` samples (ignored by the other shadings)
};

enum RayKind { RAY_PRIMARY, RAY_SHADOW, RAY_REFLECTION, RAY_REFRACTION, RAY_DIFFUSE };

// Where a ray stands in its chain: its number (1 for the primary ray; no more than `depth`) and
// its weight, the share of the pixel's colour it carries (1 for the primary ray, times the
// mirror fraction or Fresnel weight at each bounce).
struct RayChain {
    int number;
    real weight;
};

// A ray whose colour would count less than this in its pixel is not cast: 2^-12 is a sixteenth
// of one 8-bit step (1/255). Without it, clear glass, which splits every ray in two, would cast
// up to 2^depth - 1 rays per pixel (1,023 at depth 10; glass that is also a mirror, more); this is
// the adaptive tree-depth control of Hall & Greenberg, "A Testbed for Realistic Image Synthesis",
// IEEE CG&A 3(8), 1983.
const real kMinRayWeight = real(1) / 4096;

// Rays cast, by kind, and Phong highlights evaluated. Each row of the image counts into its own
// and the counts are added up at the end.
struct RayStats {
    uint64_t primary, shadow, reflection, refraction;
    uint64_t specularTerms;
    uint64_t diffuse;     // rays scattered by diffuse surfaces (`shading path`)
    uint64_t primaryHits; // primary rays that met a shape (none: main warns)
};

// One ray of a traced ray tree (`--pixel`): what it was, what it hit, the colour it brought
// back, and its parent (the node whose hit spawned it; -1 for the primary ray).
struct RayNode {
    RayKind kind;
    Ray ray;
    bool found;    // it met a shape (for a shadow ray: it was blocked)
    RayHit record; // the hit, or the blocker of a shadow ray
    color light;   // colour brought back (for a shadow ray: the light's share when visible)
    int parent;
};

// What a trace reports besides its colour: the rays it cast and, when `tree` is not null, every
// ray as a node; `current` is the node whose hit is being shaded.
struct TraceLog {
    RayStats stats;
    std::vector<RayNode> *tree;
    int current;
    uint64_t surfaces; // a hash of every shape the rays met (adaptive sampling compares them)
};

// ---- shade.cpp: lighting and the ray chain ---------------------------------------------------

// Decides which effects a render of this scene with these settings can need (see Effects).
void PlanEffects(const Scene *scene, const RenderSettings *settings, Effects *effects);

// Whether the lights, whose intensities add up to lightSum, can change how a surface of material
// m looks under the scene's shading (shade.cpp): where they cannot, it casts no shadow ray.
bool LightsCanShow(const Scene *scene, const Material *m, color lightSum);

// Colour seen along `ray`, a ray of the given kind at `chain` in its chain, leaving a surface as
// `from` says (kNoSelfHit for a primary ray). Counts it, and every ray it leads to, in log->stats
// (and records them in log->tree if that is set).
color TraceRay(const Scene *scene, const RenderSettings *settings, RayKind kind, const Ray *ray,
               const SelfHit *from, RayChain chain, TraceLog *log);

// TraceRay's second half, for a ray whose nearest hit has been searched for (`found`, and *hit
// where it is): the background on a miss, else the hit surface shaded (which may cast more rays).
// TraceEyeRays calls it for the eye rays, whose hits are searched for together.
color ShadeFound(const Scene *scene, const RenderSettings *settings, RayKind kind, const Ray *ray,
                 RayChain chain, bool found, const RayHit *hit, TraceLog *log);

// Counts a ray of this kind.
inline void CountRay(RayKind kind, RayStats *stats) {
    switch (kind) {
    case RAY_PRIMARY:
        stats->primary++;
        break;
    case RAY_SHADOW:
        stats->shadow++;
        break;
    case RAY_REFLECTION:
        stats->reflection++;
        break;
    case RAY_REFRACTION:
        stats->refraction++;
        break;
    case RAY_DIFFUSE:
        stats->diffuse++;
        break;
    }
}

// Adds a node for a ray of this kind to log->tree, which is being recorded, with log->current as
// its parent; returns the node's index.
int RecordRay(RayKind kind, const Ray *ray, TraceLog *log);

// RecordRay where a tree is being recorded, else -1, with no call (every pixel but the one
// `--pixel` names).
inline int Record(RayKind kind, const Ray *ray, TraceLog *log) {
    return log->tree ? RecordRay(kind, ray, log) : -1;
}

// Fills in node `node` of the tree (if it is one: >= 0) once its ray's answer is known: what it
// found, and the light it brings back. (By index: the tree may have moved while it grew.)
void CloseRay(TraceLog *log, int node, bool found, const RayHit *hit, color light);

// The mirror direction of d about the unit normal n: r = d - 2 (d.n) n (the assignment handout)
vec3 Reflect(vec3 d, vec3 n);

// A uniform random unit vector (the journal's random_unit_vector), from a uniform point (x, y)
// of the unit disk: the height z = 1 - 2 r^2, uniform in (-1, 1] (Archimedes: equal heights cut
// equal areas from a sphere), and the rest (x, y) times 2 sqrt(1 - r^2), which makes its length 1
// (Marsaglia, "Choosing a Point from the Surface of a Sphere", 1972).
inline vec3 RandomUnitVector(vec2 disk) {
    real r2 = disk.x * disk.x + disk.y * disk.y;
    real stretch = 2 * std::sqrt(std::max(real(0), 1 - r2)); // (r^2 may round a hair above 1)
    return {stretch * disk.x, stretch * disk.y, 1 - 2 * r2};
}

// Beyond the handouts, Ray Tracing in One Weekend's fuzzy reflection (§10.6): the tip of the unit
// mirror direction of unit d moved to a random point of a sphere of radius `fuzz` around it
// (`unit`: a random unit vector), so that the reflection spreads more the larger the sphere.
// False where the new direction points into the surface (dir.n <= 0): the book's metal absorbs
// that ray.
inline bool FuzzReflect(vec3 d, vec3 n, real fuzz, vec3 unit, vec3 *dir) {
    *dir = Reflect(d, n) + fuzz * unit;
    return Dot(*dir, n) > 0;
}

// The colour a ray that hits nothing brings back: the background; under the book's sky
// (`background ... up R G B`), the two colours blended by the height of the ray's direction,
// a = (y / |dir| + 1) / 2: the background straight down, skyUp straight up (Ray Tracing in One
// Weekend §4.2, white to blue).
inline color BackgroundColor(const Scene *scene, vec3 dir) {
    if (!scene->sky)
        return scene->background;
    real a = real(0.5) * (SafeNormalize(dir).y + 1);
    return (1 - a) * scene->background + a * scene->skyUp;
}

// Snell's law for unit d against the unit normal n (d.n <= 0), eta = n1 / n2. Writes the unit
// refracted direction to *t and returns true, or returns false for total internal reflection.
bool Refract(vec3 d, vec3 n, real eta, vec3 *t);

// Exact Fresnel reflectance of unpolarised light for cos(incident angle), eta = n1 / n2;
// 1 under total internal reflection.
real FresnelReflectance(real cosI, real eta);

// Schlick's approximation of it, R0 + (1 - R0)(1 - cos(i))^5 with R0 = ((1 - eta)/(1 + eta))^2, as
// Ray Tracing in One Weekend computes it; 1 under total internal reflection.
real SchlickReflectance(real cosI, real eta);

// Whether a material gives off light (`emit` above 0 in some channel).
inline bool Emits(const Material *m) { return m->emit.x > 0 || m->emit.y > 0 || m->emit.z > 0; }

// ---- path.cpp, path_full.cpp: `shading path` ---------------------------------------------------

// The light along `primary`, the camera ray of sample s of pixel (i, j), whose nearest hit has
// been searched for (`found`, and *hit where it is), after any number of bounces: one Monte Carlo
// path (see path.cpp). Counts its rays in log->stats, and records them in log->tree if that is
// set.
color TracePath(const Scene *scene, const RenderSettings *settings, const Ray *primary, bool found,
                const RayHit *hit, int i, int j, int s, TraceLog *log);

// The shapes whose material emits, for next-event estimation (PlanEffects): each with its area's
// square root, its normal (a triangle's) and its radiance. Shapes without area, or of an area
// beyond the range of numbers, are left out: they can be neither hit nor sampled.
void FindEmitters(const Scene *scene, std::vector<Emitter> *emitters);

// The square root of an emitting shape's surface area (FindEmitters): a
// length, like the distances it is divided into, so that their ratio, unlike an area and a
// squared distance, stays in the range of numbers at every scale.
real EmitterSqrtArea(const Scene *scene, const Emitter *e);

// ---- blur.cpp: the fuzz of a mirror under `floor` and `phong` --------------------------------

// A fuzzy mirror's direction for `ray` arriving at a hit with unit normal n (FuzzReflect), from a
// random point that is a hash of the ray and the seed: every sample of a pixel, every ray of its
// tree, reflects along a direction of its own. False where it points into the surface.
bool FuzzyMirror(real fuzz, const Ray *ray, vec3 n, int seed, vec3 *dir);

// ---- render.cpp: the render loop -------------------------------------------------------------

// Fills in what follows from the scene and the rest of *settings: the effects the render can
// need (PlanEffects) and the camera prepared for settings->width x settings->height.
void PlanRender(const Scene *scene, RenderSettings *settings);

// Renders every pixel on at most settings->threads threads into *image; adds the rays cast to
// *stats. Plans its own copy of the settings for this scene (PlanRender). Returns the number of
// threads it ran on (the calling one and those it started): no more than the image has rows, or
// than the system would start.
int Render(const Scene *scene, const RenderSettings *settings, Image *image, RayStats *stats);

// The colours of `count` eye rays (at most kEyeRaysTogether) of pixel (i, j), its samples s,
// s + 1, ...: their nearest hits searched for together (FindEyeRayHits), then each traced on as
// the scene's shading says (TracePath, or ShadeFound: the chain of rays). Every eye ray of a
// render and of a probe (--pixel) takes this one route; one sample a pixel is count = 1.
void TraceEyeRays(const Scene *scene, const RenderSettings *settings, const Ray *rays, int count,
                  int i, int j, int s, TraceLog *log, color *colours);

// The colour of pixel (i, j): the average of its samples, before clamping. `settings` must have
// been planned for this scene (PlanRender).
color RenderPixel(const Scene *scene, const RenderSettings *settings, int i, int j,
                  RayStats *stats);

// Pixel (i, j)'s sample s of n (n <= 65536, the most --spp allows), in pixels from the image's
// top-left corner.
vec2 SamplePosition(int i, int j, int s, int n);

// Colour channel to 8 bits: round(clamp(c, 0, 1) * 255), no gamma.
uint8_t ToByte(real c);

// The sRGB curve: linear light in [0, 1] to its 8-bit-ready encoding (`shading path` pixels).
real SrgbEncode(real linear);
