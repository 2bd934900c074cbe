// layout.h -- the committed scene: the layout the fast shape loop reads (commit.cpp), the search
// over it (kernel.cpp, one ray; packet.cpp, a pixel's samples together) and the BVH build
// (build.cpp). Speed machinery: every answer is the plain loop's (geometry.cpp), bit for bit.
// Included by ray.h, whose Scene holds a SceneLayout; the functions take structs that ray.h and
// render.h define (declared here, complete where the functions are called).
#pragma once
#include "numbers.h"

#include <cstddef>
#include <vector>

struct Scene;
struct Ray;
struct RayHit;
struct RayStart;
struct Triangle;
struct Methods;
struct RenderSettings;
struct TraceLog;

// ---- the layout ----------------------------------------------------------------------------

// A scene is written as the handouts' structs; once per render CommitScene (like Embree's scene
// commit) copies its triangles and its spheres into blocks of kLanes, coordinate by coordinate,
// which the kernel (kernel.cpp) tests kLanes at a time, and, for a scene large enough that it
// pays, builds a bounding volume hierarchy over the triangles. The answers are the very bits of
// the plain loop.
const int kLanes = 32 / (int)sizeof(real); // 4 doubles or 8 floats: one 256-bit vector

// An axis-aligned box, and its largest |coordinate| (TriangleBox and SlabInterval, robust.h).
struct Box {
    real lo[3], hi[3];
    real size;
};

// What a triangle's hit needs that does not depend on the ray (plane.cpp): the box that holds
// every hit (TriangleBox, the window), and the plane's normal as the first tier rounds it. The
// committed scene keeps one for each triangle (SceneLayout); the plain loop makes it as it goes.
// (The small members sit together after the box, so no padding follows each: 144 bytes in
// double, not 160, and the box's size and `flat`, which every survivor's reach test reads
// first, are within 16 bytes of each other.)
struct TriangleSetUp {
    Box box;
    int scale;          // the edges are multiplied by 2^scale before their cross product
    bool normalKnown;   // nError small against n: the first half of FirstOrderHolds (plane.cpp)
    unsigned char flat; // the axis of n's largest component: the one the plane most nearly faces
    bool hasArea;       // n is neither 0 nor beyond the range of numbers
    dvec3 n;            // (b - a) 2^scale x (c - a) 2^scale, rounded
    dvec3 nError;       // per component of n, a bound on its rounding error
    vec3 normal;        // n / |n|, for shading
    real awayShare;     // for RayHit::awayShare: > 0 where normalKnown, else 0
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

// ---- commit.cpp and kernel.cpp: committing a scene, and searching it -------------------------

// Builds scene->layout from the scene's triangles and spheres (see SceneLayout): once per render,
// after the scene is complete. The shape loop answers the same with or without it, only faster.
// The BVH is built by up to `threads` threads (two at most, one on a single core), and is the
// same bits however many build it. The layout holds copies of the shapes: a scene whose shapes
// are changed in place after it must be committed again (only a change in how many there are
// is noticed, LayoutIsCurrent in ray.h, and then the plain loop runs).
void CommitScene(Scene *scene, LayoutChoice choice, int threads = 2);

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

// ---- packet.cpp: a pixel's samples searched for together ----------------------------------

// Whether a packet of `count` rays can be taken and pays (PacketPays): the watertight and stable
// methods, a current list layout tested in AVX2 (the kernel takes no packet otherwise), two rays
// or more, and a scene small enough (at most 64 shapes) that each ray's own set-up outweighs what
// the blocks save.
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

// ---- shade.cpp, path.cpp: an eye ray whose hit a packet found ------------------------------

// What became of a surface's shadow ray toward each light, where it was cast before the surface
// was shaded (TraceEyeRays): not cast (unknown), none needed (ShadowRay found no direction),
// the light visible, or blocked. Kept for the scene's first kKnownLights lights.
enum ShadowAnswer { SHADOW_UNKNOWN, SHADOW_NO_RAY, SHADOW_VISIBLE, SHADOW_BLOCKED };
// (Eight, a byte each, so that KnownShadows is one 8-byte word: the course's scenes have one or
// two lights, and a light past the eighth is asked about when its surface is shaded, as TraceRay
// asks, with the same answer.)
const int kKnownLights = 8;
struct KnownShadows {
    signed char answer[kKnownLights]; // a ShadowAnswer for each light
};

// TraceRay for a primary ray whose nearest hit has been found already (FindNearestHitsFromEye),
// and whose surface's shadow rays may have been cast (`known`, or null): the same colour, counts
// and record.
color TraceFoundEyeRay(const Scene *scene, const RenderSettings *settings, const Ray *ray,
                       bool found, RayHit *hit, const KnownShadows *known, TraceLog *log);

// TracePath for an eye ray whose nearest hit has been found already (FindNearestHitsFromEye):
// `found`, and *hit where it is.
color TraceFoundPath(const Scene *scene, const RenderSettings *settings, const Ray *primary,
                     bool found, const RayHit *hit, int i, int j, int s, TraceLog *log);
