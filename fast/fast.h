// fast/fast.h -- the fast wing: speed machinery behind the one seam of the core (Accelerator,
// ray.h). Every answer is the plain loop's (geometry.cpp), bit for bit, found faster.
//
// main commits the scene once per render (CommitScene, commit.cpp, after Embree's
// rtcCommitScene): the triangles and spheres copied into blocks, coordinate by coordinate, and
// for a scene large enough that it pays, a bounding volume hierarchy over the triangles
// (commit_tree.cpp; build.cpp finds the splits), and over many spheres. The search (kernel.cpp)
// tests a block of shapes at a time (with its parts: kernel_blocks.h, kernel_spheres.h,
// kernel_wide.h, kernel_walk.h), and a pixel's eye rays together (kernel_packet.h), with GCC/clang
// vector extensions where the processor has AVX2 (one binary picks at run time) and lane by lane
// elsewhere, with the same answers.
#pragma once
#include "../robust/robust.h"

#include <cfloat>
#include <cstddef>
#include <cstring>
#include <string>
#include <vector>

// ---- the layout ----------------------------------------------------------------------------

// How many shapes a block holds, tested at once: one 256-bit vector of numbers.
const int kLanes = 32 / (int)sizeof(real); // 4 doubles or 8 floats: one 256-bit vector

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
    int index[kLanes];                  // each lane's place in scene->spheres; -1: empty
    unsigned filled;                    // bit `lane` set: the lane holds a sphere
};

// A node of the spheres' BVH, four children wide (Embree's BVH4): its children's boxes,
// coordinate by coordinate, so the kernel tests all four at once (SlabInterval widens them). A
// child is another node, a leaf (a run of blocks), or missing.
const int kChildren = 4;
struct BvhNode {
    real lo[3][kChildren], hi[3][kChildren]; // each child's box, axis by axis
    real size[kChildren];                    // each child's box's largest |coordinate|
    int child[kChildren];                    // an inner child's node, or a leaf child's first block
    int blocks[kChildren]; // a leaf child's blocks; 0: an inner child; -1: missing
};

// Child k of a node given its box (both trees' builds).
inline void SetChildBox(BvhNode *node, int k, const Box *box) {
    for (int axis = 0; axis < 3; axis++)
        node->lo[axis][k] = box->lo[axis], node->hi[axis][k] = box->hi[axis];
    node->size[k] = box->size;
}

// ---- the wide tree (the triangles' BVH) ----------------------------------------------------

// The triangles' BVH is eight children wide, with the children's boxes in float (Embree's BVH8,
// tinybvh's BVH8_CPU): eight boxes are one 256-bit vector a coordinate, half the bytes of four in
// double, and a ray tests all eight at once. Its leaves are runs of blocks of eight triangles,
// also in float. Float boxes and corners are not the exact ones, so they only ever cull what the
// exact test (in `real`) would refuse too: each box is rounded outward and carries rt's
// allowance (kBoxAllowance), and each block test only refuses a triangle that it has shown to lie
// outside by more than its rounding (kernel_wide.h says how). Every number is stored multiplied
// by 2^SceneLayout::wideExponent, which brings the scene's largest coordinate into [1, 2): a
// scene of radius 1e-30 or 1e30 is then as well resolved in float as one of radius 1.
const int kWide = 8;

// In the float build the wide blocks hold the triangles' own corners, and the block test is the
// exact one; in double they hold float copies, and the test only filters (kernel_wide.h).
const bool kExactWideBlocks = sizeof(real) == sizeof(float);

// The float next to f toward +infinity (up) or -infinity, for f not NaN and not already that
// infinity: the bit pattern one step further from 0 or nearer to it, and from 0 the smallest
// subnormal. (std::nextafter, without the library call.)
inline float FloatStep(float f, bool up) {
    if (f == 0)
        return up ? FLT_TRUE_MIN : -FLT_TRUE_MIN;
    uint32_t bits;
    memcpy(&bits, &f, sizeof bits);
    bits = (f > 0) == up ? bits + 1 : bits - 1;
    memcpy(&f, &bits, sizeof f);
    return f;
}

// A node: each child's box, axis by axis, rounded outward from the box widened by
// kBoxAllowance of its size; and each child: another node (child >= 0, its place), a leaf
// (child < 0: WideLeaf), or missing (child 0 with the empty box lo = +infinity, hi = -infinity,
// which no ray enters).
struct alignas(32) WideNode {
    float lo[3][kWide], hi[3][kWide];
    int child[kWide];
};

// A leaf child's code: its first block and how many (1 to kMaxWideLeafBlocks), in one negative
// int.
const int kMaxWideLeafBlocks = 8;
inline int WideLeaf(int first, int count) { return -1 - (first * kMaxWideLeafBlocks + count - 1); }
inline int LeafFirst(int code) { return (-1 - code) / kMaxWideLeafBlocks; }
inline int LeafCount(int code) { return (-1 - code) % kMaxWideLeafBlocks + 1; }

// Eight triangles, corner by corner and coordinate by coordinate, in float: in the float build
// the very corners (the block test is the exact one), in double the corners times
// 2^wideExponent, rounded (the block test bounds what that rounding can change).
struct alignas(32) WideBlock {
    float corner[9][kWide]; // a.x a.y a.z b.x b.y b.z c.x c.y c.z, lane by lane
    int index[kWide];       // each lane's place in scene->triangles; -1: empty
};

// What CommitScene builds: what pays for the scene's size, the blocks alone (a list), a BVH, or
// nothing (`--layout plain`: no accelerator, the plain loop answers every search).
enum LayoutChoice { LAYOUT_AUTO, LAYOUT_LIST, LAYOUT_BVH, LAYOUT_PLAIN };

// The committed scene, and the accelerator that searches it, which CommitScene installs in the
// scene (scene->accelerator points at `accelerator`, whose layout points here): so a layout is
// neither copied nor moved once made. It answers only for the scene it was made from, and only
// while that scene holds as many shapes as it did (else it declines, and the plain loop answers):
// a scene whose shapes are changed in place after the commit must be committed again.
struct SceneLayout {
    Accelerator accelerator;
    const Scene *scene = nullptr;      // the scene it was made from
    std::vector<TriangleBlock> blocks; // in scene order, or in BVH leaf order
    std::vector<TriangleSetUp> setUps; // the list's: each triangle's box and plane, by its place
    std::vector<WideNode> wideNodes;   // the triangles' BVH; empty: the blocks are one list
    std::vector<WideBlock> wideBlocks; // the BVH's leaves' blocks
    int wideExponent = 0;              // the wide tree's numbers are the scene's times 2^this
    std::vector<SphereBlock> sphereBlocks; // the spheres in scene order, kLanes a block, or in
                                           // the sphere BVH's leaf order
    std::vector<BvhNode> sphereNodes;      // empty: no sphere BVH, the blocks are one list
    size_t triangleCount = 0;              // the number of triangles it was built from
    size_t sphereCount = 0;                // the number of spheres it was built from
    bool vectors = false; // the kernel tests blocks in AVX2 vectors (else lane by lane)
    SceneLayout() = default;
    SceneLayout(const SceneLayout &) = delete;
    SceneLayout &operator=(const SceneLayout &) = delete;
};

// ---- commit.cpp and kernel.cpp: committing a scene, and searching it -----------------------

// Builds *layout from the scene's triangles and spheres (see SceneLayout), once per render after
// the scene is complete, and installs its accelerator in scene->accelerator; LAYOUT_PLAIN builds
// nothing and installs none. The searches answer the same with it or without, only faster. The
// BVH is built by up to `threads` threads (two at most, one on a single core), and is the same
// bits however many build it.
void CommitScene(Scene *scene, LayoutChoice choice, int threads, SceneLayout *layout);

// What --stats says of the layout: how many triangles, in what blocks, a list or a BVH, and how
// the blocks are tested.
std::string DescribeLayout(const Scene *scene, const SceneLayout *layout, double buildSeconds);

// The bytes the layout's arrays hold (their capacity: what was allocated and written), the
// scene's own shapes not counted.
size_t LayoutBytes(const SceneLayout *layout);

// The accelerator's two functions (kernel.cpp), as Accelerator declares them.
bool SearchLayout(const Accelerator *self, const Scene *scene, Methods methods, const Ray *ray,
                  const SelfHit *from, real tMax, bool anyHit, RayHit *hit);
void AnswerEyeRays(const Accelerator *self, const Scene *scene, Methods methods, const Ray *rays,
                   int count, RayHit *hits, bool *found);
// AnswerEyeRays's first step: the rays the kernel can take as packets, answered[k] set for each
// ray whose found[k] and hits[k] it wrote.
void SearchEyeRays(const Accelerator *self, const Scene *scene, Methods methods, const Ray *rays,
                   int count, RayHit *hits, bool *found, bool *answered);

// The stable sphere test (IntersectSphere) over the committed sphere blocks, in scene order,
// skipping sphere `skip`: the same hits as the plain loop's, to the bit. Each hit lowers *tMax to
// its t; with anyHit the first one ends the search. True if any sphere was hit.
bool HitCommittedSpheres(const Scene *scene, const SceneLayout *layout, int skip, const Ray *ray,
                         real tMin, real *tMax, bool anyHit, RayHit *hit);

// The watertight test (IntersectTriangle) over the committed triangles: the plain loop's hit, to
// the bit. (It shears the ray itself, ShearRayAxes, so that the numbers it spreads over its lanes
// come from registers.)
bool HitCommittedTriangles(const Scene *scene, const SceneLayout *layout, int skip, const Ray *ray,
                           real tMin, real tMax, bool anyHit, RayHit *hit);

// A packet for the kernel: `count` rays from the eye (at most kLanes), each searched for as it is
// (ScaleRay leaves it alone) with t in (0, infinity). kz: the axis of every ray's largest
// direction component (DominantAxis), which the shear makes z.
struct RayPacket {
    const Ray *rays;
    int count;
    int kz;
};

// The nearest hit of every ray of the packet at once, where every ray's DominantAxis is the
// packet's kz: found[r] and hits[r] are, to the bit, what the plain loop gives rays[r] alone.
// False, and nothing written, where the kernel cannot take a packet: no AVX2, or a BVH.
bool HitCommittedPacket(const Scene *scene, const SceneLayout *layout, const RayPacket *packet,
                        RayHit *hits, bool *found);

// The set-up the wide tree's search makes for a triangle as it needs it (kernel_setup.h), by the
// kernel's AVX2 copy or its other: SetUpTriangle's, to the bit (the tests hold them to it).
void KernelSetUp(const Triangle *tri, bool vectors, TriangleSetUp *setUp);

// True if this processor runs the kernel's AVX2 copy (CommitScene sets SceneLayout::vectors).
bool KernelHasVectors();
// The kernels this program runs, as `./ray --version` names them: "avx2" or "sse2" (x86-64, one
// chosen at run time), "neon" (aarch64), "vector extensions" (other processors), or "scalar"
// (`make RT_SCALAR=1`, or a compiler without vector extensions).
const char *KernelName();

// ---- commit_tree.cpp: the triangles' BVH (for CommitScene) ----------------------------------

// layout->wideNodes, layout->wideBlocks and layout->wideExponent for the triangles, built by up
// to `threads` threads (CommitScene).
void BuildTree(const std::vector<Triangle> &triangles, int threads, SceneLayout *layout);

// Child k of a wide node given its box, and a wide block of the triangles at places
// index[0..n) (commit.cpp): in float, times 2^exponent (WideNode, WideBlock).
void SetWideChildBox(WideNode *node, int k, const Box *box, int exponent);
void FillWideBlock(const std::vector<Triangle> &triangles, const int *index, int n, int exponent,
                   WideBlock *block);

// ---- commit_spheres.cpp: the committed spheres (for CommitScene) ----------------------------

// layout->sphereBlocks in scene order, or for a scene with many spheres (or LAYOUT_BVH) a BVH over
// those that can be hit, layout->sphereNodes, and the blocks in its leaves' order.
void CommitSpheres(const std::vector<Sphere> &spheres, LayoutChoice choice, SceneLayout *layout);

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

// How a tree's leaves hold their items: in blocks of 2^shift (kLanes for the spheres, kWide for
// the triangles), at most maxBlocks of them a leaf (a larger leaf is split even where the heuristic
// would keep it whole).
struct LeafShape {
    int shift, maxBlocks;
    real nodeCost; // what a split adds, in block tests (a node's visit, shared by its children)
};
inline int BlocksOf(int items, int shift) {
    return (int)(((unsigned)items + (1u << shift) - 1) >> shift);
}

// The items of triangles[first, last), and their bounds. `vectors`: with AVX2 (KernelHasVectors);
// the answers are the same bits either way, here and in SplitNode.
void MakeBuildItems(const Triangle *triangles, int first, int last, bool vectors, BuildItem *items,
                    NodeBounds *bounds);

// Where to split the node of items[begin, end), whose bounds are `node`: by the surface area
// heuristic, or at the median where `heuristic` is false or the centres spread too little or too
// far to bin. Reorders the items so that the first side's come first, and returns where the
// second's begin, with the bounds of both sides; -1 where a leaf costs less, or where every centre
// is the same point (and the items are left as they were).
int SplitNode(BuildItem *items, int begin, int end, const NodeBounds *node, bool heuristic,
              const LeafShape *leaves, bool vectors, NodeBounds side[2]);

// The Box of bounds, as TriangleBox makes one, and half its surface area.
void BoundsBox(const Bounds *bounds, Box *box, real *halfArea);
