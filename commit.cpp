// commit.cpp -- the committed scene: the triangles in the layout the fast loop reads.
//
// A scene is written, read and explained as the handouts' structs. Once per render, CommitScene
// (after Embree's rtcCommitScene) copies the triangles into blocks of kLanes, coordinate by
// coordinate, for the kernel (kernel.cpp) to test a block at a time; and when the scene has
// enough triangles that it pays (kBvhMinTriangles, measured), it builds a bounding volume
// hierarchy over them, by the surface area heuristic over binned centroids (Wald, "On fast
// construction of SAH-based bounding volume hierarchies", 2007; pbrt-v4 §7.3). Nothing here
// changes an answer: the kernel returns the bits the plain loop (watertight.cpp) returns.
#include "ray.h"

#include <algorithm>

// Below this many triangles the blocks are one list: a ray then tests them all, which is
// cheaper than walking a tree for the assignment's five triangles. Measured with `rtbench
// layout` (docs/speed.md): the tree wins from about this size on.
const size_t kBvhMinTriangles = 32;

// The surface area heuristic's bins per axis: 16 find splits within a few per cent of the best
// (Wald 2007) at a fraction of the cost of trying every triangle.
const int kBins = 16;

// A leaf holds at most this many blocks; one that the heuristic would keep whole but is larger
// is split anyway.
const int kMaxLeafBlocks = 4;

// Below this depth the surface area heuristic splits; deeper (a heuristic that keeps splitting
// one triangle off a long list) the median does, which halves each time: the traversal stack
// (kernel.cpp, kMaxDepth) then holds a tree of any size rt can read.
const int kMaxSahDepth = 48;

struct BuildItem {
    Box box;
    real centre[3]; // of the box: where the item is binned
    int index;      // its place in scene->triangles
};

const Box kEmptyBox = {{kInfinity, kInfinity, kInfinity}, {-kInfinity, -kInfinity, -kInfinity}, 0};

// (Plain comparisons, not fmin and fmax, which are library calls: no box here holds a NaN.)
static void Grow(Box *box, const Box *other) {
    for (int i = 0; i < 3; i++) {
        box->lo[i] = other->lo[i] < box->lo[i] ? other->lo[i] : box->lo[i];
        box->hi[i] = other->hi[i] > box->hi[i] ? other->hi[i] : box->hi[i];
    }
}

// Half the surface area: the chance that a ray that meets a box meets a box inside it is the
// ratio of their areas (for rays in all directions; the heuristic's premise).
static real HalfArea(const Box *b) {
    real dx = b->hi[0] - b->lo[0], dy = b->hi[1] - b->lo[1], dz = b->hi[2] - b->lo[2];
    if (!std::isfinite(dx) || !std::isfinite(dy) || !std::isfinite(dz))
        return kInfinity; // a box that holds a non-finite triangle (or none)
    return dx * dy + dy * dz + dz * dx;
}

static int Blocks(int triangles) { return (triangles + kLanes - 1) / kLanes; }

// The best boundary between bins of the centroids along `axis` (bins below it go left), and its
// cost in block tests: 1 for the node, plus for each side the chance that a ray meeting the
// node meets that side times that side's blocks. kInfinity if no boundary has both sides full.
static real BestSplit(const BuildItem *items, int n, int axis, real cmin, real scale,
                      const Box *node, int *split) {
    Box bins[kBins], right = kEmptyBox, left = kEmptyBox;
    int count[kBins] = {}, rightCount[kBins] = {}, leftCount = 0;
    real rightArea[kBins] = {};
    for (Box &b : bins)
        b = kEmptyBox;
    for (int i = 0; i < n; i++) {
        int k = std::min(kBins - 1, (int)((items[i].centre[axis] - cmin) * scale));
        Grow(&bins[k], &items[i].box);
        count[k]++;
    }
    for (int k = kBins - 1, total = 0; k > 0; k--) { // everything in bins k and above
        Grow(&right, &bins[k]);
        rightCount[k] = total += count[k];
        rightArea[k] = HalfArea(&right);
    }
    real best = kInfinity;
    for (int k = 1; k < kBins; k++) {
        Grow(&left, &bins[k - 1]);
        leftCount += count[k - 1];
        if (leftCount == 0 || rightCount[k] == 0)
            continue;
        real cost =
            1 + (HalfArea(&left) * Blocks(leftCount) + rightArea[k] * Blocks(rightCount[k])) /
                    HalfArea(node);
        if (cost < best)
            best = cost, *split = k;
    }
    return best;
}

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

// A node of the binary tree the heuristic builds, before it is collapsed to four children a
// node (Collapse). An inner node's first child follows it.
struct BinaryNode {
    Box box;
    int second;     // inner: the second child's place
    int firstBlock; // leaf: its blocks, firstBlock .. firstBlock + blockCount - 1
    int blockCount; // 0 for an inner node
};

struct Builder {
    const std::vector<Triangle> *triangles;
    std::vector<BuildItem> items;
    std::vector<BinaryNode> nodes;
    SceneLayout *layout; // the blocks go here as the leaves are made
};

// A leaf of items[begin, end): its triangles' blocks, in the order of their places in the scene.
static void MakeLeaf(Builder *b, int begin, int end, BinaryNode *node) {
    std::vector<int> index;
    for (int i = begin; i < end; i++)
        index.push_back(b->items[i].index);
    std::sort(index.begin(), index.end());
    node->firstBlock = (int)b->layout->blocks.size();
    node->blockCount = Blocks(end - begin);
    AppendBlocks(*b->triangles, index.data(), end - begin, b->layout);
}

// The box of the centroids of items[begin, end).
static Box CentreBox(const Builder *b, int begin, int end) {
    Box centres = kEmptyBox;
    for (int i = begin; i < end; i++) {
        const real *c = b->items[i].centre;
        Box point = {{c[0], c[1], c[2]}, {c[0], c[1], c[2]}, 0};
        Grow(&centres, &point);
    }
    return centres;
}

// Where to split items[begin, end), which it reorders so the left ones come first: the surface
// area heuristic's best boundary over the three axes, or -1 where a leaf costs less. Past
// kMaxSahDepth, or where the centroids do not spread (all in one point), at the median.
static int Partition(Builder *b, int begin, int end, const Box *node, int depth) {
    Box centres = CentreBox(b, begin, end);
    int n = end - begin, bestBin = 0, axis = 0;
    real best = kInfinity, cmin = 0, scale = 0;
    for (int k = 0; k < 3 && depth < kMaxSahDepth; k++) {
        real extent = centres.hi[k] - centres.lo[k];
        int split = 0;
        if (!(extent > 0) || !std::isfinite(extent) || !std::isfinite(kBins / extent))
            continue; // (a spread of 1e-308 would make the bins' scale infinite: the median)
        real cost = BestSplit(&b->items[begin], n, k, centres.lo[k], kBins / extent, node, &split);
        if (cost < best)
            best = cost, bestBin = split, axis = k, cmin = centres.lo[k], scale = kBins / extent;
    }
    BuildItem *first = &b->items[begin], *last = first + n;
    if (best < kInfinity) {
        if (best >= Blocks(n) && Blocks(n) <= kMaxLeafBlocks)
            return -1;
        int k = axis;
        auto left = [=](const BuildItem &it) {
            return std::min(kBins - 1, (int)((it.centre[k] - cmin) * scale)) < bestBin;
        };
        return begin + (int)(std::partition(first, last, left) - first);
    }
    for (int k = 1; k < 3; k++)
        if (centres.hi[k] - centres.lo[k] > centres.hi[axis] - centres.lo[axis])
            axis = k;
    int k = axis;
    std::nth_element(first, first + n / 2, last, [k](const BuildItem &x, const BuildItem &y) {
        return x.centre[k] < y.centre[k];
    });
    return begin + n / 2;
}

// The binary subtree over items[begin, end), depth-first: a node, its first child right after
// it, then its second. Returns the node's place.
static int BuildNode(Builder *b, int begin, int end, int depth) {
    int place = (int)b->nodes.size();
    b->nodes.emplace_back();
    BinaryNode node = {kEmptyBox, 0, 0, 0};
    for (int i = begin; i < end; i++)
        Grow(&node.box, &b->items[i].box);
    real lo = MaxComponent({node.box.lo[0], node.box.lo[1], node.box.lo[2]});
    real hi = MaxComponent({node.box.hi[0], node.box.hi[1], node.box.hi[2]});
    node.box.size = lo > hi ? lo : hi;
    int middle = end - begin <= kLanes ? -1 : Partition(b, begin, end, &node.box, depth);
    if (middle < 0) {
        MakeLeaf(b, begin, end, &node);
    } else {
        BuildNode(b, begin, middle, depth + 1);
        node.second = BuildNode(b, middle, end, depth + 1);
    }
    b->nodes[place] = node;
    return place;
}

// The four-wide node over binary node `top`'s subtree (Embree's BVH4, made from a binary tree as
// Wald, Benthin & Boulos 2008 do): it takes the two children, then opens the inner child of
// largest area, until it has four or only leaves. Returns its place.
static int Collapse(const Builder *b, int top, SceneLayout *layout) {
    const std::vector<BinaryNode> &binary = b->nodes;
    std::vector<int> kids;
    if (binary[top].blockCount > 0)
        kids = {top}; // the whole tree is one leaf
    else
        kids = {top + 1, binary[top].second};
    while (kids.size() < (size_t)kWidth) {
        int open = -1;
        for (int k = 0; k < (int)kids.size(); k++)
            if (binary[kids[k]].blockCount == 0 &&
                (open < 0 || HalfArea(&binary[kids[k]].box) > HalfArea(&binary[kids[open]].box)))
                open = k;
        if (open < 0)
            break;
        int inner = kids[open];
        kids[open] = inner + 1;
        kids.insert(kids.begin() + open + 1, binary[inner].second);
    }
    int place = (int)layout->nodes.size();
    layout->nodes.emplace_back();
    BvhNode node = {};
    for (int k = 0; k < kWidth; k++) {
        node.blocks[k] = -1; // no child
        if (k >= (int)kids.size())
            continue;
        const BinaryNode *kid = &binary[kids[k]];
        for (int axis = 0; axis < 3; axis++)
            node.lo[axis][k] = kid->box.lo[axis], node.hi[axis][k] = kid->box.hi[axis];
        node.size[k] = kid->box.size;
        node.blocks[k] = kid->blockCount;
        node.child[k] = kid->blockCount > 0 ? kid->firstBlock : Collapse(b, kids[k], layout);
    }
    layout->nodes[place] = node;
    return place;
}

void CommitScene(Scene *scene, LayoutChoice choice) {
    SceneLayout layout;
    const std::vector<Triangle> &triangles = scene->triangles;
    int n = (int)triangles.size();
    bool tree = choice == LAYOUT_BVH || (choice == LAYOUT_AUTO && (size_t)n >= kBvhMinTriangles);
    if (tree && n > 0) {
        Builder b = {&triangles, std::vector<BuildItem>(n), {}, &layout};
        for (int i = 0; i < n; i++) {
            BuildItem *it = &b.items[i];
            it->box = TriangleBox(&triangles[i]);
            for (int k = 0; k < 3; k++) // halves first: (lo + hi) / 2 could overflow
                it->centre[k] =
                    it->box.size < kInfinity ? it->box.lo[k] / 2 + it->box.hi[k] / 2 : 0;
            it->index = i;
        }
        layout.blocks.reserve(n / kLanes + n / 8 + 1);
        BuildNode(&b, 0, n, 0);
        Collapse(&b, 0, &layout);
    } else {
        std::vector<int> index(n);
        for (int i = 0; i < n; i++)
            index[i] = i;
        AppendBlocks(triangles, index.data(), n, &layout);
    }
    layout.setUps.resize(n);
    for (int i = 0; i < n; i++)
        SetUpTriangle(&triangles[i], &layout.setUps[i]);
    layout.triangleCount = triangles.size();
    layout.committed = true;
    layout.wide = KernelCanBeWide();
    scene->layout = std::move(layout);
}
