// fast/commit_spheres.cpp -- the committed spheres (CommitScene): blocks of kLanes in scene order,
// and for a scene with many spheres, a BVH over them.
//
// The tree is the same as the triangles' (commit.cpp): boxes split by the surface area heuristic
// (build.cpp's SplitNode), four children a node, leaves that are runs of blocks, so the one walk
// (kernel_walk.h) serves both. A sphere's box is its centre plus and minus its radius: every
// point the stable sphere test (IntersectSphere) reports lies on the sphere to within a few
// roundings of the numbers involved, far inside the allowance the walk widens each box by
// (kBoxAllowance). The tree is smaller than the triangles' and built on one thread: four children
// are made at once, by splitting a node in two and each half in two again, rather than from a
// binary tree collapsed afterwards. Nothing here changes an answer: the walk's leaves test their
// spheres as the plain loop does, and a tie goes to the earlier sphere.
#include "fast.h"

#include <algorithm>
#include <cmath>

// Below this depth (in binary splits) the surface area heuristic splits, and deeper the median,
// as for the triangles (commit.cpp), so the walk's stack holds any tree.
const int kMaxSahDepth = 48;

// Below this many spheres they are one list of blocks: a tree's walk costs more than testing a
// few blocks (`make bench`'s sphere table, docs/bench/speed.md).
const size_t kBvhMinSpheres = 64;

// The leaves: blocks of kLanes, at most four a leaf.
const LeafShape kSphereLeaves = {kLanes == 8 ? 3 : 2, 4, 1};

// A range of the items that will be one child of a node: a leaf, or a node of its own.
struct SphereRange {
    int begin, end;
    NodeBounds bounds;
    bool leaf; // the heuristic found a leaf cheaper than any split
};

static void GrowBounds(Bounds *b, const real lo[3], const real hi[3]) {
    for (int k = 0; k < 3; k++)
        b->lo[k] = std::min(b->lo[k], lo[k]), b->hi[k] = std::max(b->hi[k], hi[k]);
}

static NodeBounds EmptyNodeBounds() {
    Bounds empty = {{kInfinity, kInfinity, kInfinity, 0}, {-kInfinity, -kInfinity, -kInfinity, 0}};
    return {empty, empty};
}

// The spheres' items: the box c -+ r and the centre c. A sphere that no ray can hit (a radius
// that is not a positive finite number, a centre that is not finite: IntersectSphere refuses
// it) is left out of the tree. Returns how many items.
static int SphereItems(const std::vector<Sphere> &spheres, BuildItem *items, NodeBounds *bounds) {
    *bounds = EmptyNodeBounds();
    int n = 0;
    for (size_t i = 0; i < spheres.size(); i++) {
        const Sphere *s = &spheres[i];
        vec3 c = s->center;
        // (each coordinate on its own: a sum of finite ones, 1e308 + 1e308, may overflow)
        if (!(s->radius > 0) || !std::isfinite(s->radius) || !IsFinite(c))
            continue;
        BuildItem item = {}; // (zero padding: the build reads it as the centre's fourth lane)
        for (int k = 0; k < 3; k++) {
            real x = Component(c, k);
            item.lo[k] = x - s->radius, item.hi[k] = x + s->radius, item.centre[k] = x;
        }
        item.index = (int)i;
        items[n++] = item;
        GrowBounds(&bounds->box, item.lo, item.hi);
        GrowBounds(&bounds->centres, item.centre, item.centre);
    }
    return n;
}

// One block: the spheres at places index[0..n) lane by lane; an empty lane repeats lane 0's
// sphere (finite numbers, so it computes nothing unusual), with index -1, and is left out of
// `filled`.
static void FillSphereBlock(const std::vector<Sphere> &spheres, const int *index, int n,
                            SphereBlock *block) {
    block->filled = 0;
    for (int lane = 0; lane < kLanes; lane++) {
        const Sphere *s = &spheres[index[lane < n ? lane : 0]];
        for (int axis = 0; axis < 3; axis++)
            block->center[axis][lane] = Component(s->center, axis);
        block->r2[lane] = s->radius * s->radius; // (as LineMissesSphere rounds it)
        block->index[lane] = lane < n ? index[lane] : -1;
        block->filled |= (unsigned)(lane < n) << lane;
    }
}

// The spheres of items[begin, end) as blocks appended to the layout, in scene order (so that a
// leaf tests them as the plain loop would). Returns the first block.
static int AppendSphereLeaf(const std::vector<Sphere> &spheres, BuildItem *items, int begin,
                            int end, SceneLayout *layout) {
    std::sort(items + begin, items + end,
              [](const BuildItem &x, const BuildItem &y) { return x.index < y.index; });
    int first = (int)layout->sphereBlocks.size();
    for (int at = begin; at < end; at += kLanes) {
        int index[kLanes], n = std::min(kLanes, end - at);
        for (int lane = 0; lane < n; lane++)
            index[lane] = items[at + lane].index;
        layout->sphereBlocks.emplace_back();
        FillSphereBlock(spheres, index, n, &layout->sphereBlocks.back());
    }
    return first;
}

// Up to four children for the node over `whole`: it is split in two, and then the child of
// largest area that the heuristic splits, until there are four or none splits.
static int SplitFour(BuildItem *items, const SphereRange *whole, int depth, bool vectors,
                     SphereRange kids[kChildren]) {
    int count = 1;
    kids[0] = *whole;
    while (count < kChildren) {
        int open = -1;
        real area = -1;
        for (int k = 0; k < count; k++) {
            Box box;
            real half;
            BoundsBox(&kids[k].bounds.box, &box, &half);
            if (!kids[k].leaf && kids[k].end - kids[k].begin > kLanes && half > area)
                open = k, area = half;
        }
        if (open < 0)
            break;
        SphereRange r = kids[open];
        NodeBounds side[2];
        int middle = SplitNode(items, r.begin, r.end, &r.bounds, depth < kMaxSahDepth,
                               &kSphereLeaves, vectors, side);
        if (middle < 0) {
            kids[open].leaf = true;
            continue;
        }
        for (int k = count++; k > open + 1; k--)
            kids[k] = kids[k - 1];
        kids[open] = {r.begin, middle, side[0], false};
        kids[open + 1] = {middle, r.end, side[1], false};
    }
    return count;
}

// The node over `whole`, depth-first: its place in layout->sphereNodes.
static int BuildSphereNode(const std::vector<Sphere> &spheres, BuildItem *items,
                           const SphereRange *whole, int depth, bool vectors, SceneLayout *layout) {
    SphereRange kids[kChildren];
    int count = SplitFour(items, whole, depth, vectors, kids);
    int place = (int)layout->sphereNodes.size();
    layout->sphereNodes.emplace_back();
    BvhNode node = {};
    for (int k = 0; k < kChildren; k++) {
        node.blocks[k] = -1; // no child
        if (k >= count)
            continue;
        Box box;
        real half;
        BoundsBox(&kids[k].bounds.box, &box, &half);
        SetChildBox(&node, k, &box);
        bool leaf = kids[k].leaf || kids[k].end - kids[k].begin <= kLanes || count == 1;
        if (leaf) {
            node.blocks[k] = Blocks(kids[k].end - kids[k].begin);
            node.child[k] = AppendSphereLeaf(spheres, items, kids[k].begin, kids[k].end, layout);
        } else {
            node.blocks[k] = 0;
            node.child[k] = BuildSphereNode(spheres, items, &kids[k], depth + 2, vectors, layout);
        }
    }
    layout->sphereNodes[place] = node;
    return place;
}

static bool BuildSphereTree(const std::vector<Sphere> &spheres, SceneLayout *layout) {
    std::vector<BuildItem> items(spheres.size());
    SphereRange whole = {0, 0, {}, false};
    whole.end = SphereItems(spheres, items.data(), &whole.bounds);
    if (whole.end == 0) // (no sphere can be hit: the list answers that as fast)
        return false;
    BuildSphereNode(spheres, items.data(), &whole, 0, KernelHasVectors(), layout);
    return true;
}

// The spheres, kLanes to a block in scene order, for the kernel's first sphere step.
static void SphereBlocks(const std::vector<Sphere> &spheres, SceneLayout *layout) {
    int n = (int)spheres.size();
    layout->sphereBlocks.resize(Blocks(n));
    for (int first = 0; first < n; first += kLanes) {
        int index[kLanes], count = std::min(kLanes, n - first);
        for (int lane = 0; lane < count; lane++)
            index[lane] = first + lane;
        FillSphereBlock(spheres, index, count, &layout->sphereBlocks[first / kLanes]);
    }
}

void CommitSpheres(const std::vector<Sphere> &spheres, LayoutChoice choice, SceneLayout *layout) {
    bool tree = choice == LAYOUT_BVH || (choice == LAYOUT_AUTO && spheres.size() >= kBvhMinSpheres);
    if (!(tree && !spheres.empty() && BuildSphereTree(spheres, layout)))
        SphereBlocks(spheres, layout);
    layout->sphereCount = spheres.size();
}
