// fast/commit.cpp -- the committed scene: the shapes in the layout the fast search reads.
//
// A scene is written, read and explained as the handouts' structs. Once per render, CommitScene
// (after Embree's rtcCommitScene) copies the triangles, and the spheres, into blocks of kLanes,
// coordinate by coordinate, for the kernel (kernel.cpp) to test a block at a time (the spheres in
// commit_spheres.cpp); and when the scene has enough triangles that it pays (kBvhMinTriangles),
// it builds a bounding volume hierarchy over them instead (commit_tree.cpp). Nothing here changes
// an answer: the kernel returns the plain loop's bits.
#include "fast.h"

#include <algorithm>
#include <cmath>

// Below this many triangles the blocks are one list: a ray then tests them all, which is
// cheaper than walking a tree for the assignment's five triangles. `make bench` (its mesh table,
// docs/bench/speed.md) shows the tree winning from about this size on.
const size_t kBvhMinTriangles = 32;

// One block: the triangles at places index[0..n) lane by lane; empty lanes repeat lane 0's
// corners with index -1, so they cost nothing extra and are passed over by their index.
static void FillBlock(const std::vector<Triangle> &triangles, const int *index, int n,
                      TriangleBlock *block) {
    for (int lane = 0; lane < kLanes; lane++) {
        const Triangle *t = &triangles[index[lane < n ? lane : 0]];
        const vec3 corner[3] = {t->a, t->b, t->c};
        for (int k = 0; k < 9; k++)
            block->corner[k][lane] = Component(corner[k / 3], k % 3);
        block->index[lane] = lane < n ? index[lane] : -1;
    }
}

// The triangles at places index[0..n) as blocks appended to the layout, in that order.
static void AppendBlocks(const std::vector<Triangle> &triangles, const int *index, int n,
                         SceneLayout *layout) {
    for (int first = 0; first < n; first += kLanes) {
        layout->blocks.emplace_back();
        FillBlock(triangles, index + first, std::min(kLanes, n - first), &layout->blocks.back());
    }
}

// x times 2^k (two exact steps, p1 p2 = 2^k, each a normal number) as a float, rounded down
// (`down`) or up: rounded to nearest, then one step outward where that went the wrong way. (A
// product that underflows double is off by less than 2^-1074, which the walk's allowance for
// the ray, far above float's smallest step, covers.)
static float ScaledFloat(double x, double p1, double p2, bool down) {
    double scaled = x * p1 * p2;
    float f = (float)scaled;
    if (down ? (double)f > scaled : (double)f < scaled)
        f = FloatStep(f, !down);
    return f;
}

// 2^k as two factors, each a normal double (k may be up to about 2100 either way).
static void PowerFactors(int k, double *p1, double *p2) {
    *p1 = std::ldexp(1.0, k / 2), *p2 = std::ldexp(1.0, k - k / 2);
}

// Child k of a wide node: the box widened by kBoxAllowance of its size (what SlabInterval adds
// for the box; the ray's share, OriginPad, the walk adds), scaled by 2^exponent and rounded
// outward to float.
void SetWideChildBox(WideNode *node, int k, const Box *box, int exponent) {
    double p1, p2;
    PowerFactors(exponent, &p1, &p2);
    double pad = (double)kBoxAllowance * (double)box->size;
    for (int axis = 0; axis < 3; axis++) {
        node->lo[axis][k] = ScaledFloat((double)box->lo[axis] - pad, p1, p2, true);
        node->hi[axis][k] = ScaledFloat((double)box->hi[axis] + pad, p1, p2, false);
    }
}

// One wide block: the triangles at places index[0..n), lane by lane, in float (times 2^exponent
// in the double build; as they are in the float build, whose block test is the exact one);
// empty lanes repeat lane 0's corners with index -1, and are passed over by their index.
void FillWideBlock(const std::vector<Triangle> &triangles, const int *index, int n, int exponent,
                   WideBlock *block) {
    double p1, p2;
    PowerFactors(exponent, &p1, &p2);
    for (int lane = 0; lane < kWide; lane++) {
        const Triangle *t = &triangles[index[lane < n ? lane : 0]];
        const vec3 corner[3] = {t->a, t->b, t->c};
        for (int k = 0; k < 9; k++) {
            real x = Component(corner[k / 3], k % 3);
            block->corner[k][lane] = kExactWideBlocks ? (float)x : (float)((double)x * p1 * p2);
        }
        block->index[lane] = lane < n ? index[lane] : -1;
    }
}

// The set-ups (plane.cpp) of the triangles, in scene order, each made where it is kept: the
// vector is reserved and appended to, not resized (which would write every byte twice).
static void SetUpAll(const std::vector<Triangle> &triangles, SceneLayout *layout) {
    layout->setUps.reserve(triangles.size());
    for (const Triangle &t : triangles) {
        TriangleSetUp setUp;
        SetUpTriangle(&t, &setUp);
        layout->setUps.push_back(setUp);
    }
}

void CommitScene(Scene *scene, LayoutChoice choice, int threads, SceneLayout *layout) {
    layout->blocks.clear(), layout->setUps.clear();
    layout->wideNodes.clear(), layout->wideBlocks.clear(), layout->wideExponent = 0;
    layout->sphereBlocks.clear(), layout->sphereNodes.clear();
    if (choice == LAYOUT_PLAIN) {
        scene->accelerator = nullptr;
        return;
    }
    const std::vector<Triangle> &triangles = scene->triangles;
    int n = (int)triangles.size();
    bool tree = choice == LAYOUT_BVH || (choice == LAYOUT_AUTO && (size_t)n >= kBvhMinTriangles);
    if (tree && n > 0) {
        BuildTree(triangles, threads, layout);
    } else {
        std::vector<int> index(n);
        for (int i = 0; i < n; i++)
            index[i] = i;
        AppendBlocks(triangles, index.data(), n, layout);
        SetUpAll(triangles, layout);
    }
    CommitSpheres(scene->spheres, choice, layout);
    layout->triangleCount = triangles.size();
    layout->vectors = KernelHasVectors();
    layout->scene = scene;
    layout->accelerator = {layout, SearchLayout, AnswerEyeRays};
    scene->accelerator = &layout->accelerator;
}

size_t LayoutBytes(const SceneLayout *l) {
    return l->blocks.capacity() * sizeof(TriangleBlock) +
           l->setUps.capacity() * sizeof(TriangleSetUp) +
           l->wideNodes.capacity() * sizeof(WideNode) +
           l->wideBlocks.capacity() * sizeof(WideBlock) +
           l->sphereBlocks.capacity() * sizeof(SphereBlock) +
           l->sphereNodes.capacity() * sizeof(BvhNode);
}
