// path.h -- what the two estimators of `shading path` share: the path being followed, the
// decisions of each bounce and their random numbers (path_sampling.h), and a mirror's or glass's
// next ray. The journal's estimator and the entry, TracePath, are in path.cpp; rt's estimator,
// the journal's with four steps beyond it, in path_full.cpp.
#pragma once
#include "path_sampling.h"
#include "render.h"

// The decisions of one bounce, each with a hash of its own (PathHash), and the hashes of its two
// disk points: the scattered direction's and a point on an emitting sphere's (DiskPoint).
enum Decision {
    PICK_SURFACE,
    PICK_EMITTER,
    EMITTER_UV, // a pair (PathRandomPair)
    ROULETTE,
    SCATTER_DISK,
    EMITTER_DISK = SCATTER_DISK + kDiskDimensions,
    DECISIONS = EMITTER_DISK + kDiskDimensions
};
static_assert(DECISIONS <= kDimensionsPerBounce, "each bounce's numbers must be its own");

// A path being followed: its random numbers, the light gathered so far, the share of light the
// next vertex passes on to the pixel, the ray to follow, and what the last bounce was.
struct Path {
    const Scene *scene;
    const RenderSettings *settings;
    TraceLog *log;
    PathSample sample;
    int bounce;    // 0 for the primary ray's vertex
    color light;   // gathered so far (rt's estimator)
    color through; // the throughput: what the next vertex's light counts in the pixel
    Ray ray;       // the ray to follow
    SelfHit from;  // and what it must not hit (the surface it leaves)
    RayKind kind;
    real scatterPdf;  // the density the last diffuse bounce drew the ray with; 0: not diffuse
    vec3 scatteredAt; // and the point it was drawn at, on the shape (kind, index) below
    ShapeKind scatteredShape;
    int scatteredIndex;
    bool departs; // the rays from this diffuse hit start at `departure` (Depart)
    vec3 departure;
    vec3 shadingNormal; // the diffuse hit's SurfaceNormal: its lighting and scattering use it
                        // (a scattered ray must also leave on the side of its geometric normal)
};

inline real Random(const Path *path, Decision d) {
    return PathRandom(&path->sample, path->bounce, d);
}

// A mirror's or glass's next ray, for both estimators (path.cpp).
bool MirrorOrGlass(const Path *path, const Ray *in, const RayHit *hit, const Material *m, real pick,
                   Ray *out, SelfHit *from, RayKind *kind);

// rt's estimator (path_full.cpp): the path from its eye ray, whose nearest hit has been searched
// for (foundFirst, *firstHit), to its end; the light it brings to the pixel.
color FullPath(Path *path, bool foundFirst, const RayHit *firstHit);
