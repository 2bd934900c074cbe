// ray.h -- the map of rt, a teaching ray tracer.
//
// In reading order: numbers and vectors; the structs of the course handouts (Ray, Perspective,
// RayHit, Sphere, Triangle, Material, Light, Scene); the choice of numerical methods; the render's
// plumbing; then every function, grouped by the file that defines it. Plain data, free
// functions, no globals: a render reads a const Scene and a RenderSettings and nothing else.
// `real` is double, or float when built with -DRT_FLOAT (the ray_float program).
#ifndef RAY_H
#define RAY_H

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

// ---- numbers -------------------------------------------------------------------------------

#ifdef RT_FLOAT
typedef float real;
#else
typedef double real;
#endif

// No upper bound on a ray parameter.
const real kInfinity = std::numeric_limits<real>::infinity();

// pi, rounded to `real` (the path tracer's densities and areas).
const real kPi = real(3.14159265358979323846);

// Always inlined: the speed machinery's small helpers (the kernel, the BVH build, the plane
// test's common case), where a call would cost more than the work (GCC and clang).
#define RT_INLINE inline __attribute__((always_inline))

// Unit roundoff u: the largest relative error of one correctly rounded operation (half an ulp
// of 1). Every tolerance in rt is a multiple of u derived from an error bound, never a fixed
// distance in scene units, so the program behaves the same at any scene scale.
const real kUnitRoundoff = std::numeric_limits<real>::epsilon() * real(0.5);

// Gamma(n) = n u / (1 - n u) bounds the relative error of n chained floating-point operations
// (Higham, "Accuracy and Stability of Numerical Algorithms", 2002, Lemma 3.1; pbrt-v4 §6.8.1).
inline real Gamma(int n) { return (n * kUnitRoundoff) / (1 - n * kUnitRoundoff); }

// One step of a counter-based hash: the word added to the state, then SplitMix64's finaliser
// (Steele, Lea & Flood, "Fast Splittable Pseudorandom Number Generators", OOPSLA 2014). Folding
// the numbers that name a sample (pixel, sample, bounce, ...) in turn gives random bits that
// depend on nothing else, so the image never depends on which thread drew them.
inline uint64_t MixWord(uint64_t z, uint64_t word) {
    z += word + 0x9e3779b97f4a7c15ULL;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}

// ---- vectors -------------------------------------------------------------------------------

struct vec2 {
    real x, y;
};

struct vec3 {
    real x, y, z;
};

typedef vec3 color; // r, g, b in x, y, z; 1 is full intensity

inline vec3 operator+(vec3 a, vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline vec3 operator-(vec3 a, vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline vec3 operator-(vec3 a) { return {-a.x, -a.y, -a.z}; }
inline vec3 operator*(real s, vec3 a) { return {s * a.x, s * a.y, s * a.z}; }
inline vec3 operator*(vec3 a, vec3 b) { return {a.x * b.x, a.y * b.y, a.z * b.z}; }
inline real Dot(vec3 a, vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline vec3 Cross(vec3 a, vec3 b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline real Length(vec3 a) { return std::sqrt(Dot(a, a)); }
inline vec3 Normalize(vec3 a) { return (1 / Length(a)) * a; }
// The mirror direction of d about the unit normal n: r = d - 2 (d.n) n (the assignment handout)
inline vec3 Reflect(vec3 d, vec3 n) { return d - (2 * Dot(d, n)) * n; }
inline vec3 Abs(vec3 a) { return {std::fabs(a.x), std::fabs(a.y), std::fabs(a.z)}; }
// The larger of each pair, as std::fmax answers (a NaN loses to a number; of +0 and -0, where
// fmax may return either, the first), written out: std::fmax is a library call, 1% of the
// assignment's time.
inline real FMax(real a, real b) { return a >= b || b != b ? a : b; }
inline vec3 Max(vec3 a, vec3 b) { return {FMax(a.x, b.x), FMax(a.y, b.y), FMax(a.z, b.z)}; }
// a.x, a.y or a.z for axis 0, 1, 2 (the boxes of the committed scene and the BVH go axis by
// axis): an indexed load, not a chain of branches
inline real Component(vec3 a, int axis) {
    const real c[3] = {a.x, a.y, a.z};
    return c[axis];
}
inline bool IsFinite(vec3 a) {
    return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z);
}
inline real MaxComponent(vec3 a) { // of |a|, for finite a
    real m = std::fabs(a.x) > std::fabs(a.y) ? std::fabs(a.x) : std::fabs(a.y);
    return m > std::fabs(a.z) ? m : std::fabs(a.z);
}

// ---- the handouts' structs -----------------------------------------------------------------

// A ray: points origin + t * dir for t in an interval. dir need not be unit length.
struct Ray {
    vec3 origin;
    vec3 dir;
};

// The assignment handout's camera: the eye looks down -z at a screen `distance` away, `width`
// world units wide, split into widthPixels x heightPixels square pixels (the handout's screen is
// square; a non-square image keeps square pixels, so the screen is width*H/W high).
struct Perspective {
    vec3 eye;
    real distance;
    real width;
    int widthPixels;
    int heightPixels;
};

// The scene's camera, in one of the scene file's three forms. PlanRender turns a lookat camera
// into the screen form for the image's size; every pixel's ray then comes from GetCameraRay.
enum CameraKind {
    CAMERA_PERSPECTIVE, // the assignment handout's Perspective (its pixel counts set per render)
    CAMERA_SCREEN,      // the second handout's: eye e, screen corner l, edges h and v
    CAMERA_LOOKAT       // from, to, up and a vertical field of view
};

struct Camera {
    CameraKind kind;
    Perspective perspective; // CAMERA_PERSPECTIVE
    vec3 eye;                // CAMERA_SCREEN: the eye e,
    vec3 lowerLeft;          // the screen's lower-left corner l,
    vec3 horizontal;         // its bottom edge h, from l to the lower-right corner,
    vec3 vertical;           // and its left edge v, from l to the upper-left corner
    vec3 toCorner;           // l - e, the corner seen from the eye (set by PlanRender): every
                             // pixel's direction is built from it, never from l itself, so it
                             // does not depend on how far the eye is from the origin
    vec3 from, to, up;       // CAMERA_LOOKAT
    real fovDegrees;         // CAMERA_LOOKAT: vertical field of view
    bool fromScreen;         // the slides' GetRay: rays start at the pixel on the screen, with
                             // unit length (set by PlanRender from the methods)
};

enum ShapeKind { SHAPE_SPHERE, SHAPE_TRIANGLE };

// What a ray hit: the handout's fields, plus which shape (for probes and debugging) and
// pointError, the per-axis bound on the rounding error of `point` (pbrt-v4 §6.8), from which a
// ray leaving this point computes a safe origin.
struct RayHit {
    real t;          // ray parameter of the hit, in units of the ray's own dir
    vec3 point;      // hit point: on a sphere's surface, o + t d on a triangle (and on a sphere
                     // under --sphere textbook, whose point is the handout's o + t d)
    vec3 normal;     // unit geometric normal, turned to face the incoming ray
    bool frontFace;  // the ray arrived on the outward side
    int material;    // index into scene->materials
    ShapeKind shape; // which array the shape is in
    int index;       // index of the shape in that array
    vec3 pointError; // |point - exact hit point| <= pointError, per axis
    real awayShare;  // a triangle's (watertight method): how plainly a ray must leave it to pass
                     // over it (PassesOver); 0: it never does
};

struct Sphere {
    vec3 center;
    real radius;
    int material;
};

// Triangle with corners a, b, c; its outward side is the one (b - a) x (c - a) points to.
struct Triangle {
    vec3 a, b, c;
    int material;
};

// Surface description, with the scene file's defaults: white, matte, opaque. mirror = 1 is a
// perfect mirror whose own colour is not used; ior > 0 makes the material clear glass.
struct Material {
    std::string name;
    color diffuse;  // kd
    color ambient;  // ka, used by `shading phong` (defaults to kd)
    real specular;  // ks, the Phong highlight's weight (0: none)
    real shininess; // n, the Phong exponent
    real mirror;    // fraction of the reflected ray's colour mixed in, 0..1
    real ior;       // index of refraction of glass; 0 for an opaque material
    color emit;     // radiance the surface gives off, on both sides (`shading path`; 0: none)
};

struct Light {
    vec3 position;
    color intensity;
};

// The three lighting rules of the README's scene format (`shading floor|phong|path`).
enum ShadingModel {
    SHADING_FLOOR, // the assignment handout's kd * max(ambient, sum of I (N.L))
    SHADING_PHONG, // the second handout's ka Ia + sum of I (kd (N.L) + ks max(0, R.V)^n)
    SHADING_PATH   // the learning journal's diffuse scattering: light after any number of
                   // bounces, estimated by Monte Carlo paths (path.cpp)
};

// ---- the committed scene: the shapes in the layout the fast loop reads (commit.cpp) ----------

// A scene is written as the handouts' structs; once per render CommitScene (like Embree's scene
// commit) copies its triangles and its spheres into blocks of kLanes, coordinate by coordinate,
// which the kernel (kernel.cpp) tests kLanes at a time, and, for a scene large enough that it
// pays, builds a bounding volume hierarchy over the triangles. The answers are the very bits of
// the plain loop.
const int kLanes = 32 / (int)sizeof(real); // 4 doubles or 8 floats: one 256-bit vector

// An axis-aligned box, and its largest |coordinate| (TriangleBox, SlabInterval).
struct Box {
    real lo[3], hi[3];
    real size;
};

// A vector in double, whatever `real` is: plane.cpp's first tier computes in double.
struct dvec3 {
    double x, y, z;
};

// What a triangle's hit needs that does not depend on the ray (plane.cpp): the box that holds
// every hit (TriangleBox, the window), and the plane's normal as the first tier rounds it. The
// committed scene keeps one for each triangle (SceneLayout); the plain loop makes it as it goes.
struct TriangleSetUp {
    Box box;
    int scale;        // the edges are multiplied by 2^scale before their cross product
    dvec3 n;          // (b - a) 2^scale x (c - a) 2^scale, rounded
    dvec3 nError;     // per component of n, a bound on its rounding error
    bool normalKnown; // nError small against n: the first half of FirstOrderHolds (plane.cpp)
    vec3 normal;      // n / |n|, for shading
    bool hasArea;     // n is neither 0 nor beyond the range of numbers
    real awayShare;   // for RayHit::awayShare: > 0 where normalKnown, else 0
};

struct TriangleBlock {
    alignas(32) real corner[9][kLanes]; // a.x a.y a.z b.x b.y b.z c.x c.y c.z, lane by lane
    int index[kLanes];                  // each lane's place in scene->triangles; -1: empty
};

// kLanes spheres, coordinate by coordinate, for the kernel's first sphere step (LineMissesSphere,
// geometry.cpp): each centre, and r^2 rounded as that step rounds radius * radius. Block k holds
// the spheres at places k kLanes + lane; `filled` has a bit for each lane that holds one, so an
// empty lane never passes, whatever its numbers.
struct SphereBlock {
    alignas(32) real center[3][kLanes]; // x, y, z, lane by lane
    real r2[kLanes];                    // radius * radius
    unsigned filled;                    // bit `lane` set: the lane holds a sphere
};

// A node of the BVH, four children wide (Embree's BVH4): its children's boxes, as TriangleBox
// makes them and coordinate by coordinate, so the kernel tests all four at once (SlabInterval
// widens them). A child is another node, a leaf (a run of blocks), or missing.
const int kWidth = 4;
struct BvhNode {
    real lo[3][kWidth], hi[3][kWidth]; // each child's box, axis by axis
    real size[kWidth];                 // each child's box's largest |coordinate|
    int child[kWidth];                 // an inner child's node, or a leaf child's first block
    int blocks[kWidth];                // a leaf child's blocks; 0: an inner child; -1: missing
};

// What CommitScene builds: a BVH, the blocks alone (a list), or what pays for the scene's size.
enum LayoutChoice { LAYOUT_AUTO, LAYOUT_LIST, LAYOUT_BVH };

struct SceneLayout {
    std::vector<TriangleBlock> blocks; // in scene order, or in BVH leaf order
    std::vector<BvhNode> nodes;        // empty: no BVH, the blocks are one list
    std::vector<TriangleSetUp> setUps; // each triangle's box and plane, by its place in the scene
    std::vector<SphereBlock> sphereBlocks; // the spheres in scene order, kLanes a block
    size_t triangleCount = 0;              // the number of triangles it was built from
    size_t sphereCount = 0;                // the number of spheres it was built from
    bool committed = false;
    bool wide = false; // the kernel tests blocks in AVX2 vectors (else lane by lane: kernel.cpp)
    // A copy of a Scene may then be edited, so it starts uncommitted.
    SceneLayout() = default;
    SceneLayout(const SceneLayout &) {}
    SceneLayout &operator=(const SceneLayout &) {
        blocks.clear(), nodes.clear(), setUps.clear(), sphereBlocks.clear();
        triangleCount = 0, sphereCount = 0, committed = false;
        wide = false;
        return *this;
    }
    SceneLayout(SceneLayout &&) = default;
    SceneLayout &operator=(SceneLayout &&) = default;
};

// Everything a render needs to know about the world. Shapes name materials by index.
struct Scene {
    int width, height; // image size in pixels
    Camera camera;
    ShadingModel shading;
    real ambient;     // the ambient intensity: the floor, or Phong's Ia
    color background; // colour of a ray that hits nothing
    int depth;        // most rays in one chain, primary included
    std::vector<Material> materials;
    std::vector<Sphere> spheres;
    std::vector<Triangle> triangles;
    std::vector<Light> lights;
    std::vector<std::string> meshFiles; // the OBJ files `mesh` statements read, as opened: inputs
                                        // that an output must not replace
    SceneLayout layout; // set by CommitScene; the shape loop uses it only while it is current
    std::vector<std::string> warnings; // what the reader found legal but probably not meant
                                       // ("FILE:LINE: warning: ..."); main prints them
};

// ---- the numerical methods: robust, or the handouts' (geometry.cpp, handout.cpp, shade.cpp) --

// The numerical methods of a render: the robust defaults, or each method the course documents
// describe, as a careful student writes it (`--methods handout`), to teach with and to show in
// `make bench` what each robust step costs and buys. Every combination renders; each method
// brings its own honest way of leaving a surface (SelfHitMethod).
enum SphereMethod {
    SPHERE_STABLE,  // Ray Tracing Gems ch. 7: no cancellation (the default)
    SPHERE_TEXTBOOK // the assignment handout's A, B, C and discriminant B^2 - 4AC
};
enum TriangleMethod {
    TRIANGLE_WATERTIGHT, // Woop, Benthin & Wald 2013, t from the plane (the default)
    TRIANGLE_CRAMER,     // the assignment handout's Cramer's rule with variables A..M
    TRIANGLE_PLANE       // the second handout's: the plane's t, then the cross products' signs
};
// How a ray that leaves a surface (shadow, reflection, refraction) keeps from hitting it again.
enum SelfHitMethod {
    SELF_HIT_BOUND,   // start off the surface by the hit point's error bound (the default)
    SELF_HIT_EPSILON, // ignore hits closer than `epsilon` world units (the usual student fix)
    SELF_HIT_SKIP     // ignore the shape the ray leaves (the second handout's rule)
};
// Where a primary ray starts (`GetRay`).
enum CameraRayMethod {
    CAMERA_RAY_EYE,   // at the eye, direction eye -> pixel, not normalised (the second handout)
    CAMERA_RAY_SLIDES // at the pixel's point on the screen, unit direction (the slides)
};
enum FresnelMethod {
    FRESNEL_EXACT,  // the exact dielectric reflectance (the default)
    FRESNEL_SCHLICK // Schlick's approximation, as Ray Tracing in One Weekend uses it
};
struct Methods {
    SphereMethod sphere;
    TriangleMethod triangle;
    SelfHitMethod selfHit;
    real epsilon; // SELF_HIT_EPSILON's distance, in world units along the ray
    CameraRayMethod cameraRay;
    FresnelMethod fresnel;
};
// The epsilon is the lesson of the handout methods, not a tuned number: 1e-4 is a usual student
// fix (Ray Tracing in One Weekend takes 0.001), right at the assignment's scale of 1 and wrong
// far from it (docs/accuracy-and-time.md measures where). The robust methods never read it.
const Methods kRobustMethods = {SPHERE_STABLE, TRIANGLE_WATERTIGHT, SELF_HIT_BOUND,
                                real(1e-4),    CAMERA_RAY_EYE,      FRESNEL_EXACT};
const Methods kHandoutMethods = {SPHERE_TEXTBOOK, TRIANGLE_CRAMER,   SELF_HIT_EPSILON,
                                 real(1e-4),      CAMERA_RAY_SLIDES, FRESNEL_SCHLICK};

// ---- render plumbing: effects, settings, chains and trees of rays (shade.cpp, render.cpp) --

// A shape whose material emits (`emit`), by kind and place in its array.
struct Emitter {
    ShapeKind shape;
    int index;
    real area;   // EmitterArea, once per render (every light sample divides by it)
    vec3 normal; // a triangle's unit normal, once per render (every light sample uses it)
    color emit;  // its material's emitted radiance
};

// Which effects a render can need, decided once per render from the scene and the settings
// (PlanEffects); the shading code skips whole paths for the absent ones.
struct Effects {
    bool shadows;                  // lights, and shapes that could stand in their way
    bool reflection;               // a material with mirror > 0 or glass, and depth > 1
    bool refraction;               // a glass material, and depth > 1
    bool specular;                 // Phong shading, lights, and a material with ks > 0
    bool antialiasing;             // more than one sample per pixel
    bool indirect;                 // `shading path`: light scattered by diffuse surfaces
    std::vector<Emitter> emitters; // `shading path`: the shapes that emit, for next-event
                                   // estimation (path.cpp)
};

// Where a pixel's samples go (--aa).
enum SampleMethod {
    SAMPLES_GRID,    // a regular grid of cell centres
    SAMPLES_JITTER,  // one random point in each grid cell (stratified), seeded by the pixel
    SAMPLES_ADAPTIVE // centre and corners, then the rest jittered only where those five disagree
};

// Adaptive sampling refines a pixel when its first five samples (centre and corners) differ by
// more than this in a channel (0..1), or their rays met different shapes. Measured at 256 x 256
// and 16 spp against 256-spp references: 1/64, 1/32 and 1/16 give the same error (within 0.1%) on
// the assignment and test scenes, because the shapes decide at edges; 1/16 casts the fewest rays.
const real kAdaptiveContrast = real(1) / 16;

// How `shading path` estimates the light a diffuse surface scatters (path.cpp), each choice
// selectable so that `make bench` can compare them.
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
// The defaults are all zero, so `{}` asks for them.
struct PathMethods {
    ScatterMethod scatter;
    LightMethod lights;
    bool noRoulette; // only `depth` ends paths (biased); else Russian roulette does (unbiased)
    int seed;        // mixed into every random number: another seed, another (equally good) noise
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
// of one 8-bit step (1/255). Without it, glass, which splits every ray in two, would cast up to
// 2^(depth-1) rays per pixel; this is the adaptive tree-depth control of Hall & Greenberg, "A
// Testbed for Realistic Image Synthesis", IEEE CG&A 3(8), 1983.
const real kMinRayWeight = real(1) / 4096;

// Rays cast, by kind, and Phong highlights evaluated. Each row of the image counts into its own
// and the counts are added up at the end.
struct RayStats {
    uint64_t primary, shadow, reflection, refraction;
    uint64_t specularTerms;
    uint64_t diffuse; // rays scattered by diffuse surfaces (`shading path`)
};

// One ray of a traced ray tree (`--pixel`): what it was, what it hit, the colour it brought
// back, and its parent (the node whose hit spawned it; -1 for the primary ray).
struct RayNode {
    RayKind kind;
    Ray ray;
    bool hit;      // for a shadow ray: it was blocked
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

// An 8-bit RGB image, rows from the top, 3 bytes a pixel.
struct Image {
    int width, height;
    std::vector<uint8_t> pixels;
};

// ---- numerics: exact rescaling by powers of two (the shape tests, shading, cameras) --------
// Multiplying by a power of two changes only the exponent, so it is exact unless the result
// leaves the range of numbers. rt rescales any vector whose squares could overflow or underflow
// (a direction of 1e200 or 1e-200, a sphere of radius 1e-200) to a largest component in [1, 2),
// computes there, and scales the answer back: the same bits as unscaled arithmetic would give
// had it not overflowed.

// floor(log2 |x|) for finite x != 0: the exponent field, read directly (std::ilogb is a library
// call, and the shape loop asks for it on every ray); subnormal x takes the library's path.
inline int BinaryExponent(real x) {
#ifdef RT_FLOAT
    uint32_t bits;
    memcpy(&bits, &x, sizeof bits);
    int field = (int)((bits >> 23) & 0xff);
    return field != 0 ? field - 127 : std::ilogb(x);
#else
    uint64_t bits;
    memcpy(&bits, &x, sizeof bits);
    int field = (int)((bits >> 52) & 0x7ff);
    return field != 0 ? field - 1023 : std::ilogb(x);
#endif
}

// 2^k: the exponent field written directly when 2^k is a normal number, else the library's.
inline real PowerOfTwo(int k) {
    real x;
#ifdef RT_FLOAT
    if (k < -126 || k > 127)
        return std::ldexp(real(1), k);
    uint32_t bits = (uint32_t)(k + 127) << 23;
#else
    if (k < -1022 || k > 1023)
        return std::ldexp(real(1), k);
    uint64_t bits = (uint64_t)(k + 1023) << 52;
#endif
    memcpy(&x, &bits, sizeof x);
    return x;
}

// The number next to x toward +infinity (up) or -infinity: std::nextafter(x, +-infinity), bit
// for bit, without the library call (every ray that leaves a surface and every tie in the shape
// loop asks for it). Away from 0 the neighbour is the bit pattern one step further from or
// nearer to 0; from 0 it is the smallest subnormal.
inline real NextAfter(real x, bool up) {
    if (x != x || (x == (up ? kInfinity : -kInfinity)))
        return x; // NaN, or already the end it moves toward
    if (x == 0)
        return up ? std::numeric_limits<real>::denorm_min()
                  : -std::numeric_limits<real>::denorm_min();
#ifdef RT_FLOAT
    uint32_t bits;
#else
    uint64_t bits;
#endif
    memcpy(&bits, &x, sizeof bits);
    bits = (x > 0) == up ? bits + 1 : bits - 1;
    memcpy(&x, &bits, sizeof x);
    return x;
}

// x * 2^k and v * 2^k for any k (in two exact steps when 2^k itself is out of range).
inline real ScaleByPowerOfTwo(real x, int k) {
    const int kMax = std::numeric_limits<real>::max_exponent - 1;
    if (k > -kMax && k < kMax)
        return PowerOfTwo(k) * x;
    return PowerOfTwo(k - k / 2) * (PowerOfTwo(k / 2) * x);
}
inline vec3 ScaleByPowerOfTwo(vec3 v, int k) {
    return {ScaleByPowerOfTwo(v.x, k), ScaleByPowerOfTwo(v.y, k), ScaleByPowerOfTwo(v.z, k)};
}

// Sizes inside these windows can be squared and multiplied together without leaving the normal
// range of `real`, so the shape tests rescale only what lies outside: a direction whose largest
// component is within 2^+-kDirectionWindow (2^+-64 in double, 2^+-8 in float), a radius or a
// distance from a sphere's centre within 2^+-kLengthWindow (2^+-256, 2^+-32).
const int kDirectionWindow = std::numeric_limits<real>::max_exponent / 16;
const int kLengthWindow = 4 * kDirectionWindow;
inline bool WithinWindow(real m, int window) {
    return m >= PowerOfTwo(-window) && m <= PowerOfTwo(window);
}

// Whether a ray's direction is searched for as it is: inside the direction window, which
// ScaleRay (geometry.cpp) leaves alone, and which the packets (packet.cpp) require.
inline bool SearchedAsIs(vec3 dir) { return WithinWindow(MaxComponent(dir), kDirectionWindow); }

// The power of two that brings v's largest component into [1, 2): v * 2^UnitExponent(v). 0 for
// a zero or non-finite v (nothing to rescale).
inline int UnitExponent(vec3 v) {
    real m = MaxComponent(v);
    return m > 0 && std::isfinite(m) ? -BinaryExponent(m) : 0;
}

// |v| for v of any finite size, by the same rescaling.
inline real SafeLength(vec3 v) {
    int k = UnitExponent(v);
    return ScaleByPowerOfTwo(Length(ScaleByPowerOfTwo(v, k)), -k);
}

// A unit vector in the direction of v, for v of any finite size (1e-300 or 1e300), by rescaling
// before squaring. The zero vector stays zero.
inline vec3 SafeNormalize(vec3 v) {
    vec3 w = ScaleByPowerOfTwo(v, UnitExponent(v));
    real length = Length(w);
    return length > 0 ? (1 / length) * w : w;
}

// ---- boxes along a ray (plane.cpp and the BVH walk, kernel_walk.h) ---------------------------

// Where a ray's line passes through an axis-aligned box, widened by kBoxAllowance of the
// coordinates' sizes: the box test of the BVH, and the window a triangle's hit must lie in.
// Both use this one function, with the same rounding, so a node's window always holds the
// windows of the triangles below it (each step is monotonic: a larger box, larger bounds). 128 u
// is about three times the widest error bound of a triangle's hit point (plane.cpp), so a hit on
// the triangle always lies inside its window.
const real kBoxAllowance = 128 * kUnitRoundoff;

// The per-ray half: origin, 1/d per axis (an infinity for a 0 component), the allowance for the
// origin's size, and which end of each slab the ray meets first (the sign of 1/d).
struct SlabRay {
    vec3 origin, inverse;
    real originPad;   // OriginPad: the widening that comes with the ray
    bool backward[3]; // 1/d < 0 on that axis: the ray meets hi before lo
};
// The widening that comes with the ray: kBoxAllowance of its origin's size, and 4 times the
// smallest normal number, which stands in for sizes whose allowance would underflow (the
// rounding of numbers below it is absolute, 2^-1074 in double, far below this floor).
inline real OriginPad(const Ray *ray) {
    return kBoxAllowance * MaxComponent(ray->origin) + 4 * std::numeric_limits<real>::min();
}
inline SlabRay MakeSlabRay(const Ray *ray) {
    SlabRay r = {ray->origin, {1 / ray->dir.x, 1 / ray->dir.y, 1 / ray->dir.z}, OriginPad(ray), {}};
    r.backward[0] = std::signbit(r.inverse.x), r.backward[1] = std::signbit(r.inverse.y);
    r.backward[2] = std::signbit(r.inverse.z);
    return r;
}

// The interval of t in which the line is inside the box lo..hi, whose largest |coordinate| is
// `size`, widened on every side by kBoxAllowance (size + the origin's size). A 0 * infinity (a
// ray along a box face) is NaN and restricts nothing, nor does a box of non-finite size. The
// ends are taken by the sign of 1/d, not compared, so the loop has no branch to mispredict.
inline void SlabInterval(const real lo[3], const real hi[3], real size, const SlabRay *r,
                         real *tNear, real *tFar) {
    real pad = kBoxAllowance * size + r->originPad;
    const real o[3] = {r->origin.x, r->origin.y, r->origin.z};
    const real inv[3] = {r->inverse.x, r->inverse.y, r->inverse.z};
    real near = -kInfinity, far = kInfinity;
    for (int i = 0; i < 3; i++) {
        real a = ((lo[i] - pad) - o[i]) * inv[i], b = ((hi[i] + pad) - o[i]) * inv[i];
        real first = r->backward[i] ? b : a, last = r->backward[i] ? a : b;
        near = first > near ? first : near; // (NaN compares false: no restriction)
        far = last < far ? last : far;
    }
    *tNear = near, *tFar = far;
}

// A triangle's bounding box (Box). A corner that is not finite makes the box infinite: it holds
// every point, so no window or node that holds it can exclude a hit.
inline Box TriangleBox(const Triangle *tri) {
    vec3 a = tri->a, b = tri->b, c = tri->c;
    if (!IsFinite(a) || !IsFinite(b) || !IsFinite(c))
        return {{-kInfinity, -kInfinity, -kInfinity}, {kInfinity, kInfinity, kInfinity}, kInfinity};
    auto least = [](real x, real y, real z) { return x < y ? (x < z ? x : z) : (y < z ? y : z); };
    auto most = [](real x, real y, real z) { return x > y ? (x > z ? x : z) : (y > z ? y : z); };
    Box box = {{least(a.x, b.x, c.x), least(a.y, b.y, c.y), least(a.z, b.z, c.z)},
               {most(a.x, b.x, c.x), most(a.y, b.y, c.y), most(a.z, b.z, c.z)},
               0};
    real lo = MaxComponent({box.lo[0], box.lo[1], box.lo[2]});
    real hi = MaxComponent({box.hi[0], box.hi[1], box.hi[2]});
    box.size = lo > hi ? lo : hi;
    return box;
}

// ---- geometry.cpp: ray/shape intersection ----------------------------------------------------

// Writes the fields every shape fills the same way; `outwardNormal` must be unit length.
// The normal is turned to face the incoming ray, and frontFace records which side it came from;
// a ray that grazes the surface (d.N = 0, a tangent) counts as arriving from outside.
inline void SetFaceNormal(const Ray *ray, vec3 outwardNormal, RayHit *hit) {
    hit->frontFace = !(Dot(ray->dir, outwardNormal) > 0);
    hit->normal = hit->frontFace ? outwardNormal : -outwardNormal;
}

// Each intersect function returns true only for a hit with t in the open interval (tMin, tMax);
// it then fills *hit and leaves it untouched on a miss. ray->dir need not be unit length, but
// must not be zero.
bool IntersectSphere(const Sphere *s, const Ray *ray, real tMin, real tMax, RayHit *hit);
bool IntersectSphereTextbook(const Sphere *s, const Ray *ray, real tMin, real tMax,
                             RayHit *hit); // handout.cpp
bool IntersectTriangle(const Triangle *tri, const Ray *ray, real tMin, real tMax, RayHit *hit);
bool IntersectTriangleCramer(const Triangle *tri, const Ray *ray, real tMin, real tMax,
                             RayHit *hit);
bool IntersectTrianglePlane(const Triangle *tri, const Ray *ray, real tMin, real tMax, RayHit *hit);

void SetUpTriangle(const Triangle *tri, TriangleSetUp *setUp);

// The hit record of a triangle whose interior the ray passes through (plane.cpp): t from the
// triangle's plane, accurate for triangles of any length, and the point o + t d; false if t is
// outside (tMin, tMax) or within its rounding error of 0 (the ray has just left this plane).
// `setUp` is the triangle's SetUpTriangle, or null to compute it here.
bool RobustPlaneHit(const Triangle *tri, const TriangleSetUp *setUp, const Ray *ray, real tMin,
                    real tMax, RayHit *hit);

// Tier 1 of the plane's t (plane.cpp), whose numbers the kernel's packets share (plane_lanes.h):
// the unit roundoff of double and gamma(n) for it (Higham 2002, §3.1; Gamma has them for `real`).
constexpr double kU = std::numeric_limits<double>::epsilon() / 2;
constexpr double GammaD(int n) { return n * kU / (1 - n * kU); }

// Tier 2 is taken when tier 1's bound is wider than this share of t: then the hit point
// o + t d, which inherits the error of t, would sit farther off the surface than a few roundings
// of its coordinates, and probes would print digits that are not known. 32 u of `real` is twice
// what tier 1 gives a ray that meets an axis-aligned wall head-on, so ordinary hits stay in tier 1.
const double kPlainRelativeError = 32 * (double)kUnitRoundoff;

// Tier 1's bound is first order; FirstOrderHolds (plane.cpp) believes it only while the normal's
// error and n.d's error are each within this share of what they are errors of.
const double kFirstOrderShare = 1.0 / 1024;

// t and a bound on |t - t*|, where t* is the exact t of the exact plane through a, b, c.
struct PlaneT {
    double t, error;
};

// What tier 1 alone makes of a ray (QuickPlaneT, plane.cpp): a miss, a hit, or unsure, for
// RobustPlaneHit to decide from the start.
enum QuickAnswer { PLANE_MISS, PLANE_HIT, PLANE_UNSURE };

// RobustPlaneHit's record for the t it settled on: the point o + t d, which lies on the plane to
// within its bound (the rounding of o + t d itself, and t's error times |d|), the normal turned
// toward the ray. False, and *hit untouched, where the point leaves the range of numbers.
inline bool PlaneHitRecord(const Triangle *tri, const TriangleSetUp *setUp, const Ray *ray,
                           PlaneT plane, RayHit *hit) {
    real t = (real)plane.t;
    vec3 along = t * ray->dir;
    if (!IsFinite(ray->origin + along)) // t finite, but the point beyond the range of numbers
        return false;
    SetFaceNormal(ray, setUp->normal, hit); // (a miss leaves *hit as it was)
    hit->t = t;
    hit->point = ray->origin + along;
    real tError = (real)plane.error + Gamma(1) * t;
    hit->pointError = Gamma(2) * (Abs(hit->point) + Abs(along)) + tError * Abs(ray->dir);
    hit->material = tri->material;
    hit->shape = SHAPE_TRIANGLE;
    hit->awayShare = setUp->awayShare;
    return true;
}

// What a ray must not count as a hit besides t outside its interval: hits at t <= tMin, and the
// shape it leaves (index -1: none). Set by LeaveSurface and ShadowRay from the self-hit method;
// a ray from the eye starts kFromTheEye.
struct RayStart {
    real tMin;
    ShapeKind shape;
    int index;
};
const RayStart kFromTheEye = {0, SHAPE_SPHERE, -1};

// The nearest hit over every shape of the scene with t in (tMin, tMax): the one loop that serves
// primary, reflection and refraction rays.
bool FindNearestHit(const Scene *scene, Methods methods, const Ray *ray, real tMin, real tMax,
                    RayHit *hit);

// True if any shape is hit with t in (tMin, tMax); stops at the first. Serves shadow rays.
bool AnyHit(const Scene *scene, Methods methods, const Ray *ray, real tMin, real tMax);

// The same two questions for a ray that starts as `start` says, with t in (start->tMin, tMax).
bool FindNearestHitFrom(const Scene *scene, Methods methods, const Ray *ray, const RayStart *start,
                        real tMax, RayHit *hit);

bool AnyHitFrom(const Scene *scene, Methods methods, const Ray *ray, const RayStart *start,
                real tMax);

// The origin for a ray leaving hit->point in direction dir: the point pushed off the surface by
// its own error bound, to the side dir goes, so the new ray cannot hit the surface it leaves.
vec3 OffsetRayOrigin(const RayHit *hit, vec3 dir);

// Whether a ray in direction dir from a point that OffsetRayOrigin moved off triangle hit, to the
// side `side` points to, goes so plainly away from it that the shape loop may pass over it. The
// moved origin is on that side of the exact plane, or on it (OffsetRayOrigin's bound, which
// holds while the normal is known to 2^-10: normalKnown). A ray going away from the plane on
// that side can then meet it only at t <= 0, which RobustPlaneHit's sound bound refuses; passing
// over the triangle, as --self-hit skip does, changes no answer wherever that bound holds (a
// layout test checks closed meshes of triangles around spheres of radius 1e-305 to 1e300) and saves
// that refusal, about 200 instructions. Going away is certain where the rounded n.d, on that side,
// exceeds awayShare of sum |d_i| (SetUpTriangle says why). A sphere is never passed over: a ray
// leaving it inward meets it again. (Inline: every ray that leaves a surface asks.)
inline bool PassesOver(const RayHit *hit, vec3 side, vec3 dir) {
    if (!(hit->shape == SHAPE_TRIANGLE && hit->awayShare > 0))
        return false;
    real away = Dot(side, hit->normal) < 0 ? -Dot(dir, hit->normal) : Dot(dir, hit->normal);
    return away > hit->awayShare * (std::fabs(dir.x) + std::fabs(dir.y) + std::fabs(dir.z));
}

// Where such a ray starts its search: from t = 0, passing over the triangle it leaves where
// PassesOver, else over nothing.
inline RayStart StartLeaving(const RayHit *hit, vec3 side, vec3 dir) {
    return PassesOver(hit, side, dir) ? RayStart{0, SHAPE_TRIANGLE, hit->index} : kFromTheEye;
}

// The ray that leaves a hit in direction dir, and what it must not hit, by the self-hit method:
// bound, from OffsetRayOrigin, passing over the triangle it leaves where PassesOver; epsilon,
// from the hit point, ignoring hits closer than methods->epsilon; skip, from the hit point,
// ignoring the shape it leaves.
void LeaveSurface(const RayHit *hit, vec3 dir, const Methods *methods, Ray *ray, RayStart *start);

// The shadow ray from a hit to a light at lightPosition, leaving the surface as LeaveSurface
// does, with t = 1 at the light, so a blocker is any hit in (start->tMin, 1). False if the light
// is where the ray starts, where nothing can be in between.
bool ShadowRay(const RayHit *hit, vec3 lightPosition, const Methods *methods, Ray *ray,
               RayStart *start);

// ---- watertight.cpp: the watertight triangle test ----------------------------------------------

// The axis of d's largest component (of equal ones, the later axis), which the watertight
// test's shear turns into z (ShearRay).
inline int DominantAxis(vec3 d) {
    vec3 ad = Abs(d);
    return ad.x > ad.y ? (ad.x > ad.z ? 0 : 2) : (ad.y > ad.z ? 1 : 2);
}

// The per-ray half of the watertight test, shared by every triangle the ray meets: kz, the axis
// of the direction's largest component, renamed z; the ray origin with its axes renamed
// (kz + 1, kz + 2, kz); and the shear that turns the direction into the +z axis.
struct RayShear {
    int kz;
    vec3 origin;
    real sx, sy; // d[kx]/d[kz] and d[ky]/d[kz]
};
void ShearRay(const Ray *ray, RayShear *shear);

// v with its axes renamed (kx, ky, kz) = (kz + 1, kz + 2, kz) mod 3. A rotation keeps the
// triangles' winding, whatever kz is. kz is a compile-time constant, so every component below is
// a plain field, not an indexed load: the triangle loop is compiled once per axis (HitShapes).
template <int kz> inline vec3 RenameAxes(vec3 v) {
    if constexpr (kz == 0)
        return {v.y, v.z, v.x};
    else if constexpr (kz == 1)
        return {v.z, v.x, v.y};
    else
        return v;
}

// ShearRay for a ray whose kz is known (watertight.cpp explains the shear).
template <int kz> inline void ShearRayAxes(const Ray *ray, RayShear *shear) {
    vec3 d = RenameAxes<kz>(ray->dir);
    *shear = {kz, RenameAxes<kz>(ray->origin), d.x / d.z, d.y / d.z};
}

// The watertight test of one triangle for a ray whose shear is computed: as IntersectTriangle.
// `setUp` as for RobustPlaneHit.
bool IntersectWatertight(const Triangle *tri, const TriangleSetUp *setUp, const Ray *ray,
                         const RayShear *shear, real tMin, real tMax, RayHit *hit);

// The triangle half of the shape loop (HitShapes) for the watertight method: the nearest hit
// (the first, with anyHit) among triangles[0..n) but `skip`, with t in (tMin, tMax). Compiled once
// per main axis, with the first step of the test inlined: most triangles end there.
bool HitWatertightTriangles(const Triangle *triangles, int n, int skip, const Ray *ray,
                            const RayShear *shear, real tMin, real tMax, bool anyHit, RayHit *hit);

// ---- path.cpp: `shading path` -----------------------------------------------------------------

// The light along `primary`, the camera ray of sample s of pixel (i, j), after any number of
// bounces: one Monte Carlo path (see path.cpp). Counts its rays in log->stats, and records them
// in log->tree if that is set.
color TracePath(const Scene *scene, const RenderSettings *settings, const Ray *primary, int i,
                int j, int s, TraceLog *log);

// TracePath for an eye ray whose nearest hit has been found already (FindNearestHitsFromEye):
// `found`, and *hit where it is.
color TraceFoundPath(const Scene *scene, const RenderSettings *settings, const Ray *primary,
                     bool found, const RayHit *hit, int i, int j, int s, TraceLog *log);

// Whether a material gives off light (`emit` above 0 in some channel). (shade.cpp)
bool Emits(const Material *m);

// The surface area of an emitting shape. (shade.cpp, where the emitters are found)
real EmitterArea(const Scene *scene, const Emitter *e);

// ---- commit.cpp and kernel.cpp: the committed scene ------------------------------------------

// Builds scene->layout from the scene's triangles and spheres (see SceneLayout): once per render,
// after the scene is complete. The shape loop answers the same with or without it, only faster.
// The BVH is built by up to `threads` threads (two at most, one on a single core), and is the
// same bits however many build it. The layout holds copies of the shapes: a scene whose shapes
// are changed in place after it must be committed again (only a change in how many there are
// is noticed, below, and then the plain loop runs).
void CommitScene(Scene *scene, LayoutChoice choice, int threads = 2);

// True while scene->layout was built from as many triangles as the scene holds.
inline bool LayoutIsCurrent(const Scene *scene) {
    return scene->layout.committed && scene->layout.triangleCount == scene->triangles.size();
}

// True while scene->layout's sphere blocks were built from as many spheres as the scene holds.
inline bool SpheresAreCurrent(const Scene *scene) {
    return scene->layout.committed && scene->layout.sphereCount == scene->spheres.size();
}

// The stable sphere test (HitSphere, geometry.cpp) over the committed sphere blocks, in scene
// order, skipping sphere `skip`: the same hits, to the bit. Each hit lowers *tMax to its t; with
// anyHit the first one ends the search. True if any sphere was hit.
bool HitCommittedSpheres(const Scene *scene, int skip, const Ray *ray, real tMin, real *tMax,
                         bool anyHit, RayHit *hit);

// HitWatertightTriangles over the committed layout: the same hit, to the bit. (It shears the ray
// itself, ShearRayAxes, so that the numbers it spreads over its lanes come from registers.)
bool HitCommittedTriangles(const Scene *scene, int skip, const Ray *ray, real tMin, real tMax,
                           bool anyHit, RayHit *hit);

// A packet for the kernel: `count` rays (at most kLanes), each searched for as it is (ScaleRay
// leaves it alone), with its start (tMin, and the shape it leaves), and one tMax. kz: the axis
// of every ray's largest direction component (DominantAxis), which the shear makes z.
struct RayPacket {
    const Ray *rays;
    const RayStart *starts;
    int count;
    int kz;
    real tMax;
    bool anyHit; // each ray stops at its first hit, as AnyHitFrom does
};

// HitShapes for every ray of the packet at once, where every ray's DominantAxis is the packet's
// kz: found[r] and hits[r] are, to the bit, what the plain loop gives rays[r] alone (with
// anyHit, whether it is blocked). False, and nothing written, where the kernel cannot take a
// packet: no AVX2, or a BVH.
bool HitCommittedPacket(const Scene *scene, const RayPacket *packet, RayHit *hits, bool *found);

// True if this processor runs the kernel's AVX2 copy (CommitScene sets SceneLayout::wide).
bool KernelCanBeWide();

// ---- build.cpp: where the BVH build splits a node (for CommitScene) -------------------------

// A box as the build keeps it: lo and hi of x, y, z, each read as a vector of four numbers whose
// fourth is not used; aligned, so that no vector straddles two cache lines.
struct alignas(4 * sizeof(real)) Bounds {
    real lo[4], hi[4];
};

// What the build knows of a node's triangles: the union of their boxes, and the box of their
// centres (where they are binned).
struct NodeBounds {
    Bounds box, centres;
};

// A triangle as the build sees it: its box (TriangleBox), the box's centre, and its place in the
// scene. Each of lo, hi and centre is read as a vector of four, the fourth being the next number
// in the item, which is not used (the centre's is the index, and in double the 4 bytes of
// padding after it, which the centre's store sets to 0): so an item is 80 bytes (40 in float),
// moved the sooner as the build reorders them, and kLanes of them fit in a block's memory,
// where they are made (commit.cpp).
struct BuildItem {
    real lo[3], hi[3];
    real centre[3];
    int index; // in scene->triangles
};

// How many blocks hold this many triangles (a count, never negative: so a shift, not a signed
// division).
inline int Blocks(int triangles) { return (int)(((unsigned)triangles + kLanes - 1) / kLanes); }

// The items of triangles[first, last), and their bounds. `wide`: with AVX2 (KernelCanBeWide);
// the answers are the same bits either way, here and in SplitNode.
void MakeBuildItems(const Triangle *triangles, int first, int last, bool wide, BuildItem *items,
                    NodeBounds *bounds);

// Where to split the node of items[begin, end), whose bounds are `node`: by the surface area
// heuristic, or at the median where `heuristic` is false or the centres do not spread. Reorders
// the items so that the first side's come first, and returns where the second's begin, with the
// bounds of both sides; -1 where a leaf costs less (and the items are left as they were).
int SplitNode(BuildItem *items, int begin, int end, const NodeBounds *node, bool heuristic,
              bool wide, NodeBounds side[2]);

// The Box of bounds, as TriangleBox makes one, and half its surface area.
void BoundsBox(const Bounds *bounds, Box *box, real *halfArea);

// ---- shade.cpp: lighting and the ray chain ---------------------------------------------------

// Decides which effects a render of this scene with these settings can need (see Effects).
void PlanEffects(const Scene *scene, const RenderSettings *settings, Effects *effects);

// Colour seen along `ray`, a ray of the given kind at `chain` in its chain, starting as `start`
// says (kFromTheEye for a primary ray). Counts it, and every ray it leads to, in log->stats (and
// records them in log->tree if that is set).
color TraceRay(const Scene *scene, const RenderSettings *settings, RayKind kind, const Ray *ray,
               const RayStart *start, RayChain chain, TraceLog *log);

// What became of a surface's shadow ray toward each light, where it was cast before the surface
// was shaded (TraceEyeRays): not cast (unknown), none needed (ShadowRay found no direction),
// the light visible, or blocked. Kept for the scene's first kKnownLights lights.
enum ShadowAnswer { SHADOW_UNKNOWN, SHADOW_NO_RAY, SHADOW_VISIBLE, SHADOW_BLOCKED };
const int kKnownLights = 8;
struct KnownShadows {
    signed char answer[kKnownLights]; // a ShadowAnswer for each light
};

// TraceRay for a primary ray whose nearest hit has been found already (FindNearestHitsFromEye),
// and whose surface's shadow rays may have been cast (`known`, or null): the same colour, counts
// and record.
color TraceFoundEyeRay(const Scene *scene, const RenderSettings *settings, const Ray *ray,
                       bool found, RayHit *hit, const KnownShadows *known, TraceLog *log);

// Counts a ray of this kind; adds a node for it to log->tree, if a tree is being recorded, with
// log->current as its parent (returns the node's index, or -1).
void CountRay(RayKind kind, RayStats *stats);
int RecordRay(RayKind kind, const Ray *ray, TraceLog *log);

// Snell's law for unit d against the unit normal n (d.n <= 0), eta = n1 / n2. Writes the unit
// refracted direction to *t and returns true, or returns false for total internal reflection.
bool Refract(vec3 d, vec3 n, real eta, vec3 *t);

// Exact Fresnel reflectance of unpolarised light for cos(incident angle), eta = n1 / n2;
// 1 under total internal reflection.
real FresnelReflectance(real cosI, real eta);

// Schlick's approximation of it, R0 + (1 - R0)(1 - cos(i))^5 with R0 = ((1 - eta)/(1 + eta))^2, as
// Ray Tracing in One Weekend computes it; 1 under total internal reflection.
real SchlickReflectance(real cosI, real eta);

// ---- packet.cpp: a pixel's samples searched for together ----------------------------------

// Whether a packet of `count` rays can be taken and pays (PacketPays): the
// watertight and stable methods, a current list layout tested in AVX2 (the kernel takes no
// packet otherwise), two rays or more, and a scene small enough (at most 64 shapes) that each
// ray's own set-up outweighs what the blocks save.
bool PacketsPay(const Scene *scene, Methods methods, int count);

// FindNearestHitFrom for `count` rays from the eye (kFromTheEye, tMax infinity), at most kLanes:
// found[r] and hits[r] are exactly what it gives rays[r]. A pixel's samples, tested together
// where the kernel can (HitCommittedPacket: then true), one by one where it cannot.
bool FindNearestHitsFromEye(const Scene *scene, Methods methods, const Ray *rays, int count,
                            RayHit *hits, bool *found);

// AnyHitFrom for `count` rays (at most kLanes), each from its start, with one tMax: blocked[r] is
// exactly what it gives rays[r]. Shadow rays toward one light, tested together where they can be.
void AnyHitsFrom(const Scene *scene, Methods methods, const Ray *rays, const RayStart *starts,
                 int count, real tMax, bool *blocked);

// TraceRay for `count` primary rays (at most kLanes), their colours added to *sum in turn: the
// same colours, counts and sums, found faster. Their nearest hits are searched for together
// (FindNearestHitsFromEye), and where that took a packet, so are their surfaces' shadow rays
// toward each light (AnyHitsFrom).
void TraceEyeRays(const Scene *scene, const RenderSettings *settings, const Ray *rays, int count,
                  TraceLog *log, color *sum);

// ---- camera.cpp: the cameras; render.cpp: the render loop -----------------------------------

// The assignment's GetRay(Perspective, vec2, Ray*), in rt's form: the ray from the eye through
// screenCoord, given in pixels from the screen's top-left corner (pixel (i, j)'s centre is
// (i + 0.5, j + 0.5)). ray->dir is the vector from the eye to that point of the screen, not
// normalised. (The slides' own ray starts at that point with the vector normalised: GetCameraRay
// makes it under `--camera-ray slides`.)
void GetRay(Perspective p, vec2 screenCoord, Ray *ray);

// The second handout's camera: the ray from the eye through l + (x / W) h + (1 - y / H) v for
// screenCoord (x, y) in pixels from the top-left of a W x H image (the handout counts rows from
// the bottom). ray->dir is not normalised.
void GetScreenRay(const Camera *camera, int width, int height, vec2 screenCoord, Ray *ray);

// The one way every pixel's ray is made: through GetRay or GetScreenRay, per camera kind.
void GetCameraRay(const Camera *camera, int width, int height, vec2 screenCoord, Ray *ray);

// A `camera lookat` in the screen form for a W x H image, the screen one unit in front of the
// eye. Returns false, with *error saying which, if from = to, up is along the view, or fov is not
// in (0, 180).
bool LookAtToScreen(const Camera *lookAt, int width, int height, Camera *screen,
                    std::string *error);

// Whether a `camera screen` can make a ray through every pixel: h and v non-zero and not parallel,
// and the eye off the screen's plane (else every ray lies in that plane). False with *error.
bool ScreenCameraIsValid(const Camera *camera, std::string *error);

// Fills in what follows from the scene and the rest of *settings: the effects the render can
// need (PlanEffects) and the camera prepared for settings->width x settings->height.
void PlanRender(const Scene *scene, RenderSettings *settings);

// Renders every pixel on settings->threads threads into *image; adds the rays cast to *stats.
// Plans its own copy of the settings for this scene (PlanRender).
void Render(const Scene *scene, const RenderSettings *settings, Image *image, RayStats *stats);

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

// ---- image.cpp: image files and comparing images ------------------------------------------------

// Whether `output` may be written by a run that reads `inputs`: its name ends in .png or .ppm
// (or it is a device or FIFO), it is not one of the inputs, and if it exists, it is not a
// directory or a file without write permission. False with the exit status (2 bad usage, 3 I/O)
// and *error otherwise. Checked before a render, so a mistake costs no time.
bool CheckOutputPath(const std::string &output, const std::vector<std::string> &inputs, int *status,
                     std::string *error);

// Writes *image to path as 8-bit RGB, PNG or binary PPM by the name's extension. A regular file
// is written through a temporary file renamed into place (a symbolic link is followed), so the
// path holds either its old contents or the whole new image, also when SIGINT or SIGTERM
// arrives; a device or FIFO is written to directly. False with *error on failure.
bool WriteImage(const char *path, const Image *image, std::string *error);

// Reads any PNG file into *image as 8-bit RGB. Returns false and sets *error on failure.
bool ReadPng(const char *path, Image *image, std::string *error);

// How two images of the same size differ, channel values in 0..255.
struct ImageDifference {
    double rmse;     // root mean square difference over all channels
    double psnr;     // 20 log10(255 / rmse) in dB; infinite for identical images
    int largest;     // largest difference of one channel
    long pixelsOver; // pixels with a channel differing by more than the tolerance
};

// A heat scale for x in [0, 1]: black, red, yellow, white.
color HeatColor(real x);

// Compares a and b (same size) and draws *heatmap: black where equal, through red and yellow to
// white for the largest possible difference. Returns false if the sizes differ.
bool CompareImages(const Image *a, const Image *b, int tolerance, ImageDifference *difference,
                   Image *heatmap);

// ---- text.cpp: lines, tokens and numbers (scene files, probe lines, the command line) --------

// The longest line a scene file or probe file may have: a statement is a keyword and at most
// fifteen numbers, so this leaves room for any comment, and a one-line file of 250 MB is refused
// at once instead of being held in memory.
const size_t kMaxLineLength = 65536;

enum LineStatus {
    LINE_READ,     // *line holds the next line, without its \n or \r\n
    LINE_END,      // no more lines
    LINE_TOO_LONG, // the line was longer than kMaxLineLength (and has been skipped)
    LINE_BAD       // a NUL byte (not a text file) or a read error: stop reading
};

// Reads line number `lineNumber` (from 1) of a text file, without its comment (from `#` on); on
// line 1 a UTF-8 byte-order mark is skipped. Sets *error for LINE_TOO_LONG and LINE_BAD.
LineStatus ReadTextLine(FILE *file, int lineNumber, std::string *line, std::string *error);

// Splits a line into tokens at spaces and tabs, up to a `#` (the rest is a comment).
void Tokenize(const std::string &line, std::vector<std::string> *tokens);

// A token as it may be shown in a message: quoted, at most 40 characters, unprintable bytes as ?.
std::string Shown(const std::string &token);

// A message as one printable line: control characters (C0, DEL and C1, and the Unicode line and
// paragraph separators) and bytes that are not UTF-8 written as escapes, \n or \xHH a byte.
std::string PrintableLine(const std::string &text);

// Reads a number token: decimal digits with an optional sign, point and exponent, finite.
// Returns false and sets *error for anything else (inf, nan, hexadecimal, trailing characters).
bool ParseReal(const std::string &token, real *value, std::string *error);

// Whether a token is written as a whole number: an optional sign, then decimal digits, of any
// length.
bool IsWholeNumber(const std::string &token);

// Reads a whole number token (IsWholeNumber) in [lo, hi]; false with *error otherwise. Shared by
// the scene reader and the command line.
bool ParseWholeNumber(const std::string &token, int lo, int hi, int *value, std::string *error);

// ---- scene_file.cpp: scene files (docs/scene-format.md) -----------------------------------------

// The scene a file starts from: nothing in it, 512 x 512, `camera perspective 0 0 0 2 2`,
// ambient 0.2, floor shading, black background, depth 10.
void InitScene(Scene *scene);

// Reads a scene file. On failure returns false with *error = "FILE:LINE: message".
bool ReadSceneFile(const char *path, Scene *scene, std::string *error);

// Reads a scene from text, naming it fileName in errors.
bool ParseSceneText(const std::string &text, const char *fileName, Scene *scene,
                    std::string *error);

// ---- mesh.cpp: Wavefront OBJ meshes (docs/scene-format.md) --------------------------------------

// One transform word of a `mesh` statement; the words move every vertex in the order written.
enum MeshStepKind { MESH_SCALE, MESH_ROTATE, MESH_TRANSLATE };
struct MeshStep {
    MeshStepKind kind;
    real factor;       // MESH_SCALE: the uniform factor, > 0
    int axis;          // MESH_ROTATE: 0, 1, 2 for x, y, z
    real cosine, sine; // MESH_ROTATE: of the angle (exactly 0 and +-1 for multiples of 90)
    vec3 offset;       // MESH_TRANSLATE
};

// Reads the transform words tokens[first..]: `scale S`, `rotate x|y|z DEGREES`, `translate X Y
// Z`, any number of each. Returns false with *error for an unknown word or a bad value.
bool ParseMeshTransform(const std::vector<std::string> &tokens, size_t first,
                        std::vector<MeshStep> *steps, std::string *error);

// The vertex p moved by every step, in order.
vec3 TransformVertex(const std::vector<MeshStep> &steps, vec3 p);

// Reads a Wavefront OBJ file, open as `file` and called meshName in messages: every face as
// triangles of `material` (a fan from its first corner), its vertices moved by `steps`,
// appended to *triangles, at most maxTriangles of them. False with *error = "MESH:LINE: message"
// for a malformed line, a file without faces, or more triangles than that.
bool ReadObj(FILE *file, const char *meshName, int material, const std::vector<MeshStep> &steps,
             size_t maxTriangles, std::vector<Triangle> *triangles, std::string *error);

// A mesh statement's PATH as rt opens it: relative to the folder of the scene file that names it
// (an absolute path as given).
std::string MeshPath(const char *sceneFile, const std::string &path);

// The statement `mesh PATH MATERIAL [transform words]` on line `line` of sceneFile, its material
// already found: reads the file into scene->triangles (at most maxTriangles) and records it in
// scene->meshFiles. False with *error: "SCENE:LINE: message" for the statement or a file that
// cannot be opened, "MESH:LINE: message" for the file's own content.
bool ReadMeshStatement(const std::vector<std::string> &tokens, const char *sceneFile, int line,
                       int material, size_t maxTriangles, Scene *scene, std::string *error);

// ---- probe.cpp: probes and ray trees (docs/command-line.md) -------------------------------------

// Reads a probe line `OX OY OZ DX DY DZ`. Returns false with *error for a bad line; sets *blank
// (and returns true) for a blank or comment line.
bool ParseProbeLine(const std::string &line, Ray *ray, bool *blank, std::string *error);

// The JSON line for the nearest hit of `ray` with t > 0.
std::string ProbeRayJson(const Scene *scene, const RenderSettings *settings, const Ray *ray);

// The JSON line for a probe line that could not be read.
std::string ProbeErrorJson(const std::string &message);

// The JSON ray tree of pixel (x, y)'s centre ray.
std::string PixelTreeJson(const Scene *scene, const RenderSettings *settings, int x, int y);

// ---- views.cpp: debug views -----------------------------------------------------------------

enum ViewKind { VIEW_NORMAL, VIEW_DEPTH, VIEW_ID, VIEW_COST, VIEW_SHADOW };

// Looks up a view by its command-line name; false if there is none. ViewName is the reverse.
bool FindView(const std::string &name, ViewKind *view);
const char *ViewName(ViewKind view);

// Renders a debug view of the primary hits instead of the lit image.
void RenderView(const Scene *scene, const RenderSettings *settings, ViewKind view, Image *image,
                RayStats *stats);

// ---- scene_default.cpp, scene_test.cpp: the built-in scenes ----------------------------------

void BuildDefaultScene(Scene *scene); // the assignment scene (the handout's scene;
                                      // scenes/reference.scene holds it as a file)
void BuildTestScene(Scene *scene);    // rt's own test scene

#endif
