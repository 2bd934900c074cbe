// ray.h -- the map of rt, a teaching ray tracer: what a scene is, and how a ray meets it.
//
// In reading order: the structs of the course handouts (Ray, Perspective, Camera, RayHit, Sphere,
// Triangle, Material, Light, Scene); the choice of numerical methods; then the functions, grouped
// by the file that defines them: the cameras, where rays meet shapes, the built-in scenes. How a
// render lights what the rays hit is in render.h. Plain data, free functions, no globals.
//
// The handouts' steps, in the order a pixel takes them, are these functions:
//   GetRay                         the assignment's camera                   camera.cpp
//   FindEyeRayHits,                the nearest hit over the list of shapes   geometry.cpp
//   FindNearestHit, AnyHit         (a pixel's eye rays, any other ray); a
//                                  shadow ray's any hit
//   LightVisible                   the hard shadow of a point light          geometry.cpp
//   IntersectSphere,               a ray and one shape (the handouts' own    geometry.cpp,
//   IntersectTriangle              forms beside them: *Textbook, *Cramer,    robust/
//                                  *Plane)
//   TraceRay                       the chain of rays: lighting, shadows,     shade.cpp
//                                  mirrors, glass, at most `depth` rays
//   Reflect, Refract               the mirror direction; Snell's law         shade.cpp
//   TracePath                      light that bounces (the journal)          path.cpp
// The rest is rt's own: settings, sampling (a pixel's eye rays go GetRay, then TraceEyeRays,
// render.cpp), the robust steps beyond the handouts, and the seam.
// Beside this core, by role: robust/ (the robust triangle test and the rescaling of rays, called
// at lines marked `// robust/:`), fast/ (speed machinery, which main installs behind one seam:
// Accelerator, below; lines marked `// fast/:`) and app/ (the command line, files, probes). The
// core includes none of fast/ and app/. To read the core without them: `make reading` writes it,
// solved, to build/reading/; to step through the plain loop in a debugger, `./ray --layout plain`.
#pragma once

#include "numbers.h"

#include <cstdint>
#include <string>
#include <vector>

// ---- the handouts' structs -----------------------------------------------------------------

// A ray: points origin + t * dir for t in an interval. dir need not be unit length.
struct Ray {
    vec3 origin;
    vec3 dir;
};

// The assignment handout's camera: the eye looks down -z at a screen `distance` away,
// screenWidth world units wide, split into widthPixels x heightPixels square pixels (the
// handout's screen is square; a non-square image keeps square pixels, so the screen is
// screenWidth * H / W high).
struct Perspective {
    vec3 eye;
    real distance;
    real screenWidth;
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
    Perspective perspective;    // CAMERA_PERSPECTIVE
    vec3 eye;                   // CAMERA_SCREEN: the eye e,
    vec3 lowerLeft;             // the screen's lower-left corner l,
    vec3 horizontal;            // its bottom edge h, from l to the lower-right corner,
    vec3 vertical;              // and its left edge v, from l to the upper-left corner
    vec3 toCorner;              // l - e, the corner seen from the eye (set by PlanRender): every
                                // pixel's direction is built from it, never from l itself, so it
                                // does not depend on how far the eye is from the origin
    vec3 lookFrom, lookAt, vup; // CAMERA_LOOKAT (the scene file's from, to and up)
    real fovDegrees;            // CAMERA_LOOKAT: vertical field of view
    bool fromScreen;            // the slides' GetRay: rays start at the pixel on the screen, with
                                // unit length (set by PlanRender from the methods)
    // CAMERA_LOOKAT's thin lens (Ray Tracing in One Weekend's defocus blur): rays start on a disk
    // of radius lensRadius around the eye, across the view, and meet on the plane in focus,
    // focusDistance in front of it (the book's focus_dist). A radius of 0 is the pinhole camera:
    // every ray starts at the eye and everything is in focus.
    real lensRadius = 0;
    real focusDistance = 1;
    vec3 lensU = {0, 0, 0}, lensV = {0, 0, 0}; // the disk's two radii, right and up (set by
                                               // LookAtToScreen)
    int seed = 0; // the render's --seed, which the lens's random points depend on (PlanRender)
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
    real awayShare;  // a triangle's (robust method): how plainly a ray must leave it to pass
                     // over it (PassesOver, robust/robust.h); 0: it never does
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

// The unit normals a smooth mesh gives a triangle's corners (a mesh file's `vn`, or averaged over
// the faces around each vertex: the mesh statement's `smooth`), each on the triangle's outward
// side; all three 0 for a flat triangle. Only shading reads them (SurfaceNormal, smooth.cpp).
struct CornerNormals {
    vec3 a, b, c;
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
    // Beyond the handouts, Ray Tracing in One Weekend's metal: a mirror's reflected light times
    // `tint` (the book's albedo), along directions spread by `fuzz`, the radius of the fuzz sphere
    // (0: the sharp mirror). With their defaults a mirror is the handouts' own.
    real fuzz = 0;
    color tint = {1, 1, 1};
};

struct Light {
    vec3 position;
    color intensity;
};

// Whether the light gives any light (an intensity of 0 0 0 is legal, and lights nothing).
inline bool Shines(const Light *light) {
    return light->intensity.x > 0 || light->intensity.y > 0 || light->intensity.z > 0;
}

// The three lighting rules of the README's scene format (`shading floor|phong|path`).
enum ShadingModel {
    SHADING_FLOOR, // the assignment handout's kd * max(ambient, sum of I (N.L))
    SHADING_PHONG, // the second handout's ka Ia + sum of I (kd (N.L) + ks max(0, R.V)^n)
    SHADING_PATH   // the learning journal's diffuse scattering: light after any number of
                   // bounces, estimated by Monte Carlo paths (path.cpp)
};

struct Accelerator; // speed machinery behind the searches (the seam, below)

// The triangles one `mesh` statement made: scene->triangles[first, first + count), from `path`.
struct MeshRange {
    std::string path;
    size_t first, count;
};

// Everything a render needs to know about the world. Shapes name materials by index.
struct Scene {
    int width, height; // image size in pixels
    Camera camera;
    ShadingModel shading;
    real ambientLight; // the ambient intensity: the floor, or Phong's Ia (`ambient` in a file)
    color background;  // colour of a ray that hits nothing (looking straight down, under a sky)
    bool sky = false;  // the book's sky: background blended with skyUp by the ray's height
    color skyUp = {0, 0, 0}; // (BackgroundColor, render.h)
    int depth;               // most rays in one chain, primary included
    std::vector<Material> materials;
    std::vector<Sphere> spheres;
    std::vector<Triangle> triangles;
    std::vector<CornerNormals> cornerNormals; // empty (every triangle flat), or one a triangle
    std::vector<Light> lights;
    std::vector<std::string> meshFiles; // the OBJ files `mesh` statements read, as opened: inputs
                                        // that an output must not replace
    std::vector<MeshRange> meshes;      // what each mesh statement made, for --stats
    std::vector<std::string> warnings;  // what the reader found legal but probably not meant
                                        // ("FILE:LINE: warning: ..."); main prints them
    const Accelerator *accelerator = nullptr; // installed by main (fast/); null: every search
                                              // is the plain loop of geometry.cpp
};

// An 8-bit RGB image, rows from the top, 3 bytes a pixel.
struct Image {
    int width, height;
    std::vector<uint8_t> pixels;
};

// ---- the numerical methods: robust, or the handouts' -----------------------------------------

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

// ---- camera.cpp: the cameras -----------------------------------------------------------------

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

// The one way every pixel's ray is made: through GetRay or GetScreenRay, per camera kind; for a
// camera with a lens, through GetLensRay (GetLensCameraRay).
void GetCameraRay(const Camera *camera, int width, int height, vec2 screenCoord, Ray *ray);

// A `camera lookat` in the screen form for a W x H image, the screen one unit in front of the
// eye, with its lens's radii. Returns false, with *error saying which, if from = to, up is along
// the view, or fov is not in (0, 180).
bool LookAtToScreen(const Camera *camera, int width, int height, Camera *screen,
                    std::string *error);

// Beyond the handouts, Ray Tracing in One Weekend's thin lens, for a lookat camera in the screen
// form (LookAtToScreen): the ray from the point `lens` of the lens disk (a point of the unit
// disk, scaled by the lens's radii) through screenCoord's point on the plane in focus, which it
// reaches at t = 1. (From the lens's centre, the pinhole's GetScreenRay scaled to that plane.)
void GetLensRay(const Camera *camera, int width, int height, vec2 screenCoord, vec2 lens, Ray *ray);

// GetCameraRay for a camera with a lens: GetLensRay from a random point of the lens, a hash of
// screenCoord and camera->seed, so that every sample of every pixel has a point of its own
// (blur.cpp).
void GetLensCameraRay(const Camera *camera, int width, int height, vec2 screenCoord, Ray *ray);

// ---- geometry.cpp: where rays meet shapes ----------------------------------------------------

// Writes the fields every shape fills the same way; `outwardNormal` must be unit length.
// The normal is turned to face the incoming ray, and frontFace records which side it came from;
// a ray that grazes the surface (d.N = 0, a tangent) counts as arriving from outside.
// Checked by TestNormals (tests/test_handout.cpp).
inline void SetFaceNormal(const Ray *ray, vec3 outwardNormal, RayHit *hit) {
    hit->frontFace = !(Dot(ray->dir, outwardNormal) > 0);
    hit->normal = hit->frontFace ? outwardNormal : -outwardNormal;
}

// Each intersect function returns true only for a hit with t in the open interval (tMin, tMax);
// it then fills *hit and leaves it untouched on a miss. ray->dir need not be unit length, but
// must not be zero. The handouts' own forms (the slide's quadratic, Cramer's rule, the second
// handout's plane test), then rt's robust ones (the stable sphere; the watertight triangle,
// robust/watertight.cpp).
bool IntersectSphereTextbook(const Sphere *s, const Ray *ray, real tMin, real tMax, RayHit *hit);
bool IntersectTriangleCramer(const Triangle *tri, const Ray *ray, real tMin, real tMax,
                             RayHit *hit);
bool IntersectTrianglePlane(const Triangle *tri, const Ray *ray, real tMin, real tMax, RayHit *hit);
bool IntersectSphere(const Sphere *s, const Ray *ray, real tMin, real tMax, RayHit *hit);
bool IntersectTriangle(const Triangle *tri, const Ray *ray, real tMin, real tMax, RayHit *hit);

// What a ray that leaves a surface must not count as a hit, besides t past tMax: hits at
// t <= tMin, and the shape it leaves (index -1: none). Set by LeaveSurface and ShadowRay from the
// self-hit method; a ray from the eye has kNoSelfHit.
struct SelfHit {
    real tMin;
    ShapeKind shape;
    int index;
};
const SelfHit kNoSelfHit = {0, SHAPE_SPHERE, -1};

// The nearest hit over every shape of the scene with t in (tMin, tMax): the one loop that serves
// primary, reflection and refraction rays.
bool FindNearestHit(const Scene *scene, Methods methods, const Ray *ray, real tMin, real tMax,
                    RayHit *hit);

// True if any shape is hit with t in (tMin, tMax); stops at the first. Serves shadow rays.
bool AnyHit(const Scene *scene, Methods methods, const Ray *ray, real tMin, real tMax);

// The same two questions for a ray that leaves a surface, with t in (from->tMin, tMax).
bool FindNearestHitFrom(const Scene *scene, Methods methods, const Ray *ray, const SelfHit *from,
                        real tMax, RayHit *hit);
bool AnyHitFrom(const Scene *scene, Methods methods, const Ray *ray, const SelfHit *from,
                real tMax);

// FindNearestHit(rays[k], 0, infinity) for `count` rays from the eye (a pixel's samples, at most
// kEyeRaysTogether): found[k] and hits[k] are exactly what it gives each. An accelerator may
// search them together.
const int kEyeRaysTogether = 8;
void FindEyeRayHits(const Scene *scene, Methods methods, const Ray *rays, int count, RayHit *hits,
                    bool *found);

// The ray that leaves a hit on a shape of `scene` in direction dir, and what it must not hit, by
// the self-hit method: bound, from LeavingPoint (robust/robust.h), passing over the triangle it
// leaves where PassesOver; epsilon, from the hit point, ignoring hits closer than
// methods->epsilon; skip, from the hit point, ignoring the shape it leaves.
void LeaveSurface(const Scene *scene, Methods methods, const RayHit *hit, vec3 dir, Ray *ray,
                  SelfHit *from);

// The shadow ray from a hit to a light at lightPosition, leaving the surface as LeaveSurface
// does, with t = 1 at the light, so a blocker is any hit in (from->tMin, 1). False if the light
// is where the ray starts, where nothing can be in between.
bool ShadowRay(const Scene *scene, Methods methods, const RayHit *hit, vec3 lightPosition, Ray *ray,
               SelfHit *from);

// The assignment's hard shadow: true if nothing lies between the hit and a light at
// lightPosition (the shadow ray meets no shape at t < 1).
bool LightVisible(const Scene *scene, Methods methods, const RayHit *hit, vec3 lightPosition);

// ---- smooth.cpp: the shading normal of a smooth mesh ----------------------------------------

// The barycentric weights w of point p on triangle t: p = w[0] a + w[1] b + w[2] c, each in [0, 1].
void Barycentric(const Triangle *t, vec3 p, real w[3]);

// Whether the hit is on a triangle whose corners carry normals (scene->cornerNormals; a flat
// triangle's are all 0). Asked of every hit, so inline: most scenes have none at all.
inline bool HasCornerNormals(const Scene *scene, const RayHit *hit) {
    if (scene->cornerNormals.empty() || hit->shape != SHAPE_TRIANGLE ||
        (size_t)hit->index >= scene->cornerNormals.size())
        return false;
    vec3 a = scene->cornerNormals[hit->index].a;
    return a.x != 0 || a.y != 0 || a.z != 0;
}

// SurfaceNormal (below) where the hit has corner normals.
vec3 SmoothNormal(const Scene *scene, const RayHit *hit);

// The normal that lighting uses at a hit: a smooth mesh's corner normals interpolated at the hit
// point, turned to the side the ray came from; anywhere else the geometric normal, hit->normal.
// A light that this normal faces but the flat triangle does not is seen or not as the shadow ray
// finds: from a smooth mesh it starts where the curved surface would be (robust/leave.cpp), and
// the triangle it leaves is tested too, so light through a closed mesh's back is blocked by it.
inline vec3 SurfaceNormal(const Scene *scene, const RayHit *hit) {
    return HasCornerNormals(scene, hit) ? SmoothNormal(scene, hit) : hit->normal;
}

// Where a ray that leaves `hit` in direction dir starts under the self-hit bound. Off a flat
// triangle or a sphere, LeavingPoint (robust/robust.h). Off a smooth mesh's triangle, always on
// the side `toward` points to (the side the hit was seen from, for a shadow ray): moved out to
// where the curved surface would be (TerminatorOrigin) where the way there, and as far again,
// meets no shape; else off the flat triangle, as LeavingPoint moves it.
vec3 DeparturePoint(const Scene *scene, Methods methods, const RayHit *hit, vec3 dir, vec3 toward);

// ---- the seam: speed machinery that main may install (fast/) --------------------------------

// The plain loop over the list of shapes, as the handouts write it: every search above, where no
// accelerator is installed. (anyHit: stop at the first hit, as AnyHit does.)
bool SearchList(const Scene *scene, Methods methods, const Ray *ray, const SelfHit *from, real tMax,
                bool anyHit, RayHit *hit);

// Another way to answer the searches above, bit for bit as SearchList answers, only faster: the
// shapes in blocks tested several at a time, a bounding volume hierarchy over the triangles, a
// pixel's eye rays tested together (fast/fast.h). main installs one in scene->accelerator; the
// core calls it at two marked lines (Search, FindEyeRayHits) and never looks inside. `search`
// answers every search it is given, as SearchList does (and runs SearchList itself where it cannot,
// as for the handouts' methods); `eyeRays` answers every ray FindEyeRayHits is given, as its plain
// loop would.
struct Accelerator {
    const void *layout; // what it searches (fast/: the committed scene)
    bool (*search)(const Accelerator *self, const Scene *scene, Methods methods, const Ray *ray,
                   const SelfHit *from, real tMax, bool anyHit, RayHit *hit);
    void (*eyeRays)(const Accelerator *self, const Scene *scene, Methods methods, const Ray *rays,
                    int count, RayHit *hits, bool *found);
};

// ---- scene_default.cpp, scene_test.cpp: the built-in scenes ----------------------------------

// The scene every scene starts from (the built-in ones and every scene file): nothing in it,
// 512 x 512, `camera perspective 0 0 0 2 2`, ambient 0.2, floor shading, black background,
// depth 10.
void InitScene(Scene *scene);

void BuildDefaultScene(Scene *scene); // the assignment scene (the handout's scene;
                                      // scenes/reference.scene holds it as a file)
void BuildTestScene(Scene *scene);    // rt's own test scene
