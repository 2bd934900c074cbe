// ray.h -- the map of rt, a teaching ray tracer.
//
// In reading order: the structs of the course handouts (Ray, Perspective, RayHit, Sphere,
// Triangle, Material, Light, Scene); the choice of numerical methods; the render's plumbing; then
// every function a render calls, grouped by the file that defines it. Plain data, free functions,
// no globals: a render reads a const Scene and a RenderSettings and nothing else.
// The numbers and vectors are in numbers.h (`real` is double, or float when built with -DRT_FLOAT,
// the ray_float program); the rest has headers by role: layout.h, the committed scene and its
// fast search; robust.h, the parts of the robust triangle test that files share; io.h, files,
// text, probes and debug views.
#ifndef RAY_H
#define RAY_H

#include "layout.h"
#include "numbers.h"

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

// True while scene->layout was built from as many triangles as the scene holds.
inline bool LayoutIsCurrent(const Scene *scene) {
    return scene->layout.committed && scene->layout.triangleCount == scene->triangles.size();
}

// True while scene->layout's sphere blocks were built from as many spheres as the scene holds.
inline bool SpheresAreCurrent(const Scene *scene) {
    return scene->layout.committed && scene->layout.sphereCount == scene->spheres.size();
}

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

// ---- scene_file.cpp: scene files (docs/scene-format.md) -----------------------------------------

// The scene a file starts from: nothing in it, 512 x 512, `camera perspective 0 0 0 2 2`,
// ambient 0.2, floor shading, black background, depth 10.
void InitScene(Scene *scene);

// Reads a scene file. On failure returns false with *error = "FILE:LINE: message".
bool ReadSceneFile(const char *path, Scene *scene, std::string *error);

// Reads a scene from text, naming it fileName in errors.
bool ParseSceneText(const std::string &text, const char *fileName, Scene *scene,
                    std::string *error);

// ---- scene_default.cpp, scene_test.cpp: the built-in scenes ----------------------------------

void BuildDefaultScene(Scene *scene); // the assignment scene (the handout's scene;
                                      // scenes/reference.scene holds it as a file)
void BuildTestScene(Scene *scene);    // rt's own test scene

#endif
