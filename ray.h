// ray.h -- the map of rt, a teaching ray tracer.
//
// Every struct of the course handouts (Perspective, Ray, RayHit, Sphere, Triangle, Material,
// Light, Scene) and every function, grouped by the file that defines it. Plain data, free
// functions, no globals: a render reads a const Scene and a RenderSettings and nothing else.
// `real` is double, or float when built with -DRT_FLOAT (the ray_float program).
#ifndef RAY_H
#define RAY_H

#include <cmath>
#include <cstdint>
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

// Unit roundoff u: the largest relative error of one correctly rounded operation (half an ulp
// of 1). Every tolerance in rt is a multiple of u derived from an error bound, never a fixed
// distance in scene units, so the program behaves the same at any scene scale.
const real kUnitRoundoff = std::numeric_limits<real>::epsilon() * real(0.5);

// Gamma(n) = n u / (1 - n u) bounds the relative error of n chained floating-point operations
// (Higham, "Accuracy and Stability of Numerical Algorithms", 2002, Lemma 3.1; pbrt-v4 §6.8.1).
inline real Gamma(int n) { return (n * kUnitRoundoff) / (1 - n * kUnitRoundoff); }

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
inline vec3 Abs(vec3 a) { return {std::fabs(a.x), std::fabs(a.y), std::fabs(a.z)}; }
inline vec3 Max(vec3 a, vec3 b) {
    return {std::fmax(a.x, b.x), std::fmax(a.y, b.y), std::fmax(a.z, b.z)};
}
inline real Component(vec3 a, int axis) { return axis == 0 ? a.x : axis == 1 ? a.y : a.z; }
inline bool IsFinite(vec3 a) {
    return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z);
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

enum ShapeKind { SHAPE_SPHERE, SHAPE_TRIANGLE };

// What a ray hit: the handout's fields, plus which shape (for probes and debugging) and
// pointError, the per-axis bound on the rounding error of `point` (pbrt-v4 §6.8), from which a
// ray leaving this point computes a safe origin.
struct RayHit {
    real t;          // ray parameter of the hit, in units of the ray's own dir
    vec3 point;      // hit point, computed on the surface (not as origin + t * dir)
    vec3 normal;     // unit geometric normal, turned to face the incoming ray
    bool frontFace;  // the ray arrived on the outward side
    int material;    // index into scene->materials
    ShapeKind shape; // which array the shape is in
    int index;       // index of the shape in that array
    vec3 pointError; // |point - exact hit point| <= pointError, per axis
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

// Surface description. mirror = 1 is a perfect mirror whose own colour is not used.
struct Material {
    std::string name;
    color diffuse; // kd
    real mirror;   // fraction of the reflected ray's colour mixed in, 0..1
};

struct Light {
    vec3 position;
    color intensity;
};

// Everything a render needs to know about the world. Shapes name materials by index.
struct Scene {
    Perspective camera;
    real ambient;     // the handout's ambient floor
    color background; // colour of a ray that hits nothing
    int depth;        // most rays in one chain, primary included
    std::vector<Material> materials;
    std::vector<Sphere> spheres;
    std::vector<Triangle> triangles;
    std::vector<Light> lights;
};

// Which ray/triangle routine FindNearestHit and AnyHit use.
enum TriangleMethod {
    TRIANGLE_WATERTIGHT, // Woop, Benthin & Wald 2013 (the default)
    TRIANGLE_CRAMER      // the handout's Cramer's rule with variables A..M
};

// How one render is done; filled from the scene and the command line.
struct RenderSettings {
    int width, height;   // image size in pixels
    int samplesPerPixel; // primary rays per pixel, on a regular grid
    int depth;           // most rays in one chain, primary included
    int threads;         // worker threads; the image never depends on it
    TriangleMethod triangleMethod;
    bool showProgress; // redraw a progress line on standard error
};

// Rays cast, by kind. Each thread counts into its own and the counts are added at the end.
struct RayStats {
    uint64_t primary, shadow, reflection, refraction;
};

// An 8-bit RGB image, rows from the top, 3 bytes a pixel.
struct Image {
    int width, height;
    std::vector<uint8_t> pixels;
};

// ---- geometry.cpp: ray/shape intersection ----------------------------------------------------

// Each intersect function returns true only for a hit with t in the open interval (tMin, tMax);
// it then fills *hit and leaves it untouched on a miss. ray->dir need not be unit length, but
// must not be zero.
bool IntersectSphere(const Sphere *s, const Ray *ray, real tMin, real tMax, RayHit *hit);
bool IntersectTriangle(const Triangle *tri, const Ray *ray, real tMin, real tMax, RayHit *hit);
bool IntersectTriangleCramer(const Triangle *tri, const Ray *ray, real tMin, real tMax,
                             RayHit *hit);

// The nearest hit over every shape of the scene with t in (tMin, tMax): the one loop that serves
// primary, reflection and refraction rays.
bool FindNearestHit(const Scene *scene, TriangleMethod method, const Ray *ray, real tMin, real tMax,
                    RayHit *hit);

// True if any shape is hit with t in (tMin, tMax); stops at the first. Serves shadow rays.
bool AnyHit(const Scene *scene, TriangleMethod method, const Ray *ray, real tMin, real tMax);

// The origin for a ray leaving hit->point in direction dir: the point pushed off the surface by
// its own error bound, to the side dir goes, so the new ray cannot hit the surface it leaves.
vec3 OffsetRayOrigin(const RayHit *hit, vec3 dir);

// ---- shade.cpp: lighting and the ray chain ---------------------------------------------------

// Colour seen along `ray`, which is ray number `rayNumber` of its chain (1 = primary).
color TraceRay(const Scene *scene, const RenderSettings *settings, const Ray *ray, int rayNumber,
               RayStats *stats);

// ---- render.cpp: the camera and the render loop ------------------------------------------------

// The handout's GetRay: the ray from the eye through screenCoord, given in pixels from the
// screen's top-left corner (pixel (i, j)'s centre is (i + 0.5, j + 0.5)). ray->dir is the
// vector from the eye to that point of the screen, not normalised.
void GetRay(Perspective p, vec2 screenCoord, Ray *ray);

// Renders every pixel on settings->threads threads into *image; adds the rays cast to *stats.
void Render(const Scene *scene, const RenderSettings *settings, Image *image, RayStats *stats);

// The colour of pixel (i, j): the average of its samples, before clamping.
color RenderPixel(const Scene *scene, const RenderSettings *settings, int i, int j,
                  RayStats *stats);

// Colour channel to 8 bits: round(clamp(c, 0, 1) * 255), no gamma.
uint8_t ToByte(real c);

// ---- image.cpp: PNG files --------------------------------------------------------------------

// Writes *image to path as an 8-bit RGB PNG, through a temporary file renamed into place, so
// the path holds either its old contents or the whole new image. Returns false and sets *error
// on failure.
bool WritePng(const char *path, const Image *image, std::string *error);

// Reads any PNG file into *image as 8-bit RGB. Returns false and sets *error on failure.
bool ReadPng(const char *path, Image *image, std::string *error);

// ---- scene_default.cpp, scene_test.cpp: the built-in scenes ----------------------------------

void BuildDefaultScene(Scene *scene); // the assignment scene (SPEC section 6)
void BuildTestScene(Scene *scene);    // rt's own test scene

#endif
