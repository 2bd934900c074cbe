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
#include <condition_variable>
#include <cstring>
#include <deque>
#include <memory>
#include <mutex>
#include <thread>

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

// The build works on vectors of four numbers (GCC/Clang vector extensions, as in kernel.cpp):
// a box is lo and hi of x, y, z, each a vector whose fourth lane is free. Union, difference and
// comparison are exact, lane by lane, so every box here has the bits of TriangleBox's.
typedef real Quad4 __attribute__((vector_size(4 * sizeof(real))));
typedef int Int4 __attribute__((vector_size(16)));

#if defined(__x86_64__) && defined(__GNUC__)
#define RT_AVX2 __attribute__((target("avx2")))
#else
#define RT_AVX2
#endif
#define RT_INLINE inline __attribute__((always_inline))
// Vectors are passed by value only to functions always inlined (kernel.cpp says why).
#pragma GCC diagnostic ignored "-Wpsabi"

struct alignas(4 * sizeof(real)) Bounds { // (aligned: a vector never straddles two lines)
    real lo[4], hi[4];                    // read and written as vectors (Load, Store)
};

static RT_INLINE void Load(Quad4 *v, const real *p) { memcpy(v, p, sizeof *v); }
static RT_INLINE void Store(real *p, const Quad4 *v) { memcpy(p, v, sizeof *v); }
static RT_INLINE void Splat(Quad4 *v, real x) { *v = Quad4{x, x, x, x}; }

static RT_INLINE Bounds EmptyBounds() {
    Bounds b;
    for (int i = 0; i < 4; i++)
        b.lo[i] = kInfinity, b.hi[i] = -kInfinity;
    return b;
}

// (Plain comparisons, not fmin and fmax, which are library calls: no box here holds a NaN.)
static RT_INLINE void GrowBy(Bounds *b, const Quad4 *otherLo, const Quad4 *otherHi) {
    Quad4 lo, hi;
    Load(&lo, b->lo), Load(&hi, b->hi);
    lo = *otherLo < lo ? *otherLo : lo, hi = *otherHi > hi ? *otherHi : hi;
    Store(b->lo, &lo), Store(b->hi, &hi);
}
static RT_INLINE void Grow(Bounds *b, const Bounds *other) {
    Quad4 lo, hi;
    Load(&lo, other->lo), Load(&hi, other->hi);
    GrowBy(b, &lo, &hi);
}
static RT_INLINE void GrowPoint(Bounds *b, const Quad4 *point) { GrowBy(b, point, point); }

// The Box of bounds, with its largest |coordinate| as TriangleBox computes it.
static Box ToBox(const Bounds *b) {
    Box box = {{b->lo[0], b->lo[1], b->lo[2]}, {b->hi[0], b->hi[1], b->hi[2]}, 0};
    real lo = MaxComponent({box.lo[0], box.lo[1], box.lo[2]});
    real hi = MaxComponent({box.hi[0], box.hi[1], box.hi[2]});
    box.size = lo > hi ? lo : hi;
    return box;
}

// Half the surface area: the chance that a ray that meets a box meets a box inside it is the
// ratio of their areas (for rays in all directions; the heuristic's premise). A box that holds a
// non-finite triangle has infinite area: a side that is infinite makes a product infinite, or
// 0 * infinity, NaN, and either way the answer is kInfinity.
static RT_INLINE real HalfArea(const Bounds *b) {
    Quad4 lo, hi;
    Load(&lo, b->lo), Load(&hi, b->hi);
    Quad4 d = hi - lo;
    real area = d[0] * d[1] + d[1] * d[2] + d[2] * d[0];
    return area == area ? area : kInfinity;
}

static int Blocks(int triangles) { return (triangles + kLanes - 1) / kLanes; }

// A triangle as the build sees it: its box (TriangleBox), the box's centre, where it is binned,
// and its place in the scene. Each of lo, hi and centre is read as a vector of four, the fourth
// lane being the next number in the item: the vectors' fourth lanes are not used (kept finite
// or not, they are passed over), and an item is 80 bytes (40 in float), moved the sooner by the
// partitions.
struct BuildItem {
    real lo[3], hi[3];
    real centre[3];
    int index; // in scene->triangles
    int zero;  // (so that the centre's vector reads no unset bytes)
};
static_assert(offsetof(BuildItem, centre) + sizeof(Quad4) <= sizeof(BuildItem), "a vector past");

static RT_INLINE void GrowItem(Bounds *b, const BuildItem *item) {
    Quad4 lo, hi;
    Load(&lo, item->lo), Load(&hi, item->hi);
    GrowBy(b, &lo, &hi);
}
// The centre as a vector, its fourth lane 0. (That lane would be the index's bits: a subnormal
// number, which costs a processor some hundred cycles an operation.)
static RT_INLINE void LoadCentre(const BuildItem *item, Quad4 *c) {
    typedef decltype(*c < *c) Mask4;
    Mask4 keep = {-1, -1, -1, 0};
    Load(c, item->centre);
    *c = (Quad4)((Mask4)*c & keep);
}
static RT_INLINE void GrowCentre(Bounds *b, const BuildItem *item) {
    Quad4 c;
    LoadCentre(item, &c);
    GrowPoint(b, &c);
}

// The bins of a node's centroids on all three axes, filled in one pass (Wald 2007, §3.1): per
// bin, how many and the union of their boxes. An axis whose centroids do not spread has scale 0.
struct Bins {
    Bounds box[3][kBins];
    int count[3][kBins];
    real lo[4], scale[4]; // per axis (the fourth is 0)
};

// The items' boxes added to the bins of their centroids, the three bins found at once.
template <bool kWide>
static RT_INLINE void AddItem(const BuildItem *item, const Quad4 *lo, const Quad4 *scale,
                              Bins *bins) {
    Quad4 itemLo, itemHi, centre, last; // (read once: the bins' stores could alias them)
    Load(&itemLo, item->lo), Load(&itemHi, item->hi), LoadCentre(item, &centre);
    Splat(&last, kBins - 1);
    Quad4 f = (centre - *lo) * *scale;
    f = f < last ? f : last; // (before the conversion: the same as after; NaN gives last)
    Int4 k = __builtin_convertvector(f, Int4);
    for (int axis = 0; axis < 3; axis++) {
        bins->count[axis][k[axis]]++;
        GrowBy(&bins->box[axis][k[axis]], &itemLo, &itemHi);
    }
}

template <bool kWide> static RT_INLINE void FillBins(const BuildItem *items, int n, Bins *bins) {
    for (int axis = 0; axis < 3; axis++)
        for (int k = 0; k < kBins; k++)
            bins->box[axis][k] = EmptyBounds(), bins->count[axis][k] = 0;
    Quad4 lo, scale;
    Load(&lo, bins->lo), Load(&scale, bins->scale);
    for (int i = 0; i < n; i++)
        AddItem<kWide>(&items[i], &lo, &scale, bins);
}

// A split of a node's items: bins below `bin` of `axis` go left; what it costs.
struct Split {
    real cost;
    int axis, bin;
};

// The best boundary between the bins of `axis` (bins below it go left), and its cost in block
// tests: 1 for the node, plus for each side the chance that a ray meeting the node meets that
// side times that side's blocks. Only boundaries right after a full bin are tried: one after an
// empty bin splits the same way, and the first of those is the one a sweep over all finds.
static RT_INLINE void BestSplit(const Bins *bins, int axis, real nodeArea, Split *best) {
    const Bounds *box = bins->box[axis];
    const int *count = bins->count[axis];
    int full[kBins], m = 0;
    for (int k = 0; k < kBins; k++) // (without a branch: which bins are full is a coin toss)
        full[m] = k, m += count[k] > 0;
    if (m < 2)
        return;
    real rightCost[kBins]; // area times blocks
    Bounds right = box[full[m - 1]];
    int rightCount = count[full[m - 1]];
    rightCost[m - 1] = HalfArea(&right) * Blocks(rightCount);
    for (int j = m - 2; j > 0; j--) { // everything in full bins j and above
        Grow(&right, &box[full[j]]);
        rightCount += count[full[j]];
        rightCost[j] = HalfArea(&right) * Blocks(rightCount);
    }
    Bounds left = box[full[0]];
    int leftCount = count[full[0]];
    for (int j = 1; j < m; j++) {
        if (j > 1)
            Grow(&left, &box[full[j - 1]]), leftCount += count[full[j - 1]];
        real cost = 1 + (HalfArea(&left) * Blocks(leftCount) + rightCost[j]) / nodeArea;
        if (cost < best->cost)
            *best = {cost, axis, full[j - 1] + 1};
    }
}

// What BuildNode knows of a node's items before it looks at them: their boxes' union, and the
// box of their centroids.
struct NodeBounds {
    Bounds box, centres;
};

// The boxes of the two sides of a split: the unions of their bins.
static RT_INLINE void SideBoxes(const Bins *bins, const Split *split, NodeBounds side[2]) {
    side[0].box = side[1].box = EmptyBounds();
    for (int k = 0; k < kBins; k++)
        if (bins->count[split->axis][k] > 0)
            Grow(&side[k >= split->bin].box, &bins->box[split->axis][k]);
}

// Reorders items[begin, end) so the left ones (by the split) come first, as std::partition
// does (Hoare's scheme), and gathers each side's centroid box on the way; returns the first
// right one. An item is left where its bin, the whole part of f = (c - lo) scale, is below the
// split's, that is where f is: the binning's f, compared without the conversion.
static RT_INLINE int PartitionItems(BuildItem *items, int begin, int end, const Bins *bins,
                                    const Split *split, NodeBounds side[2]) {
    int first = begin, last = end, axis = split->axis;
    real lo = bins->lo[axis], scale = bins->scale[axis], bound = (real)split->bin;
    auto isLeft = [=](const BuildItem *item) { return (item->centre[axis] - lo) * scale < bound; };
    Bounds left = EmptyBounds(), right = EmptyBounds();
    for (;;) {
        for (;; first++) { // past the left items at the front
            if (first == last)
                return side[0].centres = left, side[1].centres = right, first;
            if (!isLeft(&items[first]))
                break;
            GrowCentre(&left, &items[first]);
        }
        GrowCentre(&right, &items[first]);
        for (last--;; last--) { // past the right items at the back
            if (first == last)
                return side[0].centres = left, side[1].centres = right, first;
            if (isLeft(&items[last]))
                break;
            GrowCentre(&right, &items[last]);
        }
        GrowCentre(&left, &items[last]);
        std::swap(items[first], items[last]);
        first++;
    }
}

// The bounds of items[begin, end).
static RT_INLINE NodeBounds Gather(const BuildItem *items, int begin, int end) {
    NodeBounds bounds = {EmptyBounds(), EmptyBounds()};
    for (int i = begin; i < end; i++)
        GrowItem(&bounds.box, &items[i]), GrowCentre(&bounds.centres, &items[i]);
    return bounds;
}

// Where to split items[begin, end), which it reorders so the left ones come first, and the
// bounds of both sides: the surface area heuristic's best boundary over the three axes, or -1
// where a leaf costs less. Past kMaxSahDepth, or where the centroids do not spread (all in one
// point), at the median. With AVX2 (the kernel's dispatch, kernel.cpp) a box is two vectors,
// not four halves: the same operations, so the same bits.
template <bool kWide>
static RT_INLINE int PartitionNode(BuildItem *items, int begin, int end, const NodeBounds *node,
                                   int depth, NodeBounds side[2]) {
    int n = end - begin;
    Bins bins;
    Split best = {kInfinity, 0, 0};
    bool spread = false;
    for (int k = 0; k < 3; k++) {
        // (a spread of 1e-308 would make the bins' scale infinite: the median)
        real extent = node->centres.hi[k] - node->centres.lo[k];
        bool usable = extent > 0 && std::isfinite(extent) && std::isfinite(kBins / extent);
        bins.lo[k] = usable ? node->centres.lo[k] : 0;
        bins.scale[k] = usable ? kBins / extent : 0;
        spread = spread || usable;
    }
    bins.lo[3] = bins.scale[3] = 0;
    if (depth < kMaxSahDepth && spread) {
        FillBins<kWide>(items + begin, n, &bins);
        real area = HalfArea(&node->box);
        for (int k = 0; k < 3; k++)
            if (bins.scale[k] > 0)
                BestSplit(&bins, k, area, &best);
    }
    if (best.cost < kInfinity) {
        if (best.cost >= Blocks(n) && Blocks(n) <= kMaxLeafBlocks)
            return -1;
        SideBoxes(&bins, &best, side);
        return PartitionItems(items, begin, end, &bins, &best, side);
    }
    int axis = 0;
    for (int k = 1; k < 3; k++)
        if (node->centres.hi[k] - node->centres.lo[k] >
            node->centres.hi[axis] - node->centres.lo[axis])
            axis = k;
    BuildItem *first = items + begin;
    std::nth_element(
        first, first + n / 2, first + n,
        [axis](const BuildItem &x, const BuildItem &y) { return x.centre[axis] < y.centre[axis]; });
    side[0] = Gather(items, begin, begin + n / 2), side[1] = Gather(items, begin + n / 2, end);
    return begin + n / 2;
}
static int PartitionPlain(BuildItem *items, int begin, int end, const NodeBounds *node, int depth,
                          NodeBounds side[2]) {
    return PartitionNode<false>(items, begin, end, node, depth, side);
}
RT_AVX2 static int PartitionWide(BuildItem *items, int begin, int end, const NodeBounds *node,
                                 int depth, NodeBounds side[2]) {
    return PartitionNode<true>(items, begin, end, node, depth, side);
}

// A node of the binary tree the heuristic builds, before it is collapsed to four children a
// node (Collapse). The tree is built in parts, one per task (BuildTasks); an inner node's first
// child follows it in its part, its second is elsewhere in the part or the root of another.
struct BinaryNode {
    Box box;
    real area;  // HalfArea of the box
    int second; // inner: the second child's place in this part, or -1 - the task of its part
    int first;  // leaf: its first item
    int count;  // leaf: its triangles; 0 for an inner node
    int block;  // leaf: its first block, once the whole tree is known (NumberLeaves)
};

// A subtree to build: over items[begin, end), at `depth`, with these bounds.
struct Task {
    int begin, end, depth;
    NodeBounds bounds;
};

// The shared state of the build's threads: the tasks made so far and each one's part of the
// tree. A part's nodes depend only on its items, so the tree is the same whichever thread builds
// which part, and in whatever order.
struct Builder {
    BuildItem *items;
    bool wide; // binning with AVX2 (KernelCanBeWide)
    std::mutex lock;
    std::condition_variable wake;
    std::vector<Task> tasks;                   // by id, in the order they were made
    std::deque<std::vector<BinaryNode>> parts; // by task id (a deque: a part stays put)
    int next;                                  // the first task not yet taken
    int unfinished;                            // tasks made and not yet done
};

// A subtree of at least this many triangles is left to any thread (a new task) rather than
// built at once by the thread that splits it off: large enough that a task costs little
// beside its work, small enough that the two threads finish about together.
const int kTaskMin = 2048;

static int AddTask(Builder *b, const Task *task) {
    std::lock_guard<std::mutex> hold(b->lock);
    b->tasks.push_back(*task);
    b->parts.emplace_back();
    b->unfinished++;
    b->wake.notify_one();
    return (int)b->tasks.size() - 1;
}

// The binary subtree over items[begin, end), depth-first into `part`: a node, its first child
// right after it, then its second (or a task for it). A leaf's items are sorted by place: its
// triangles keep their order in the scene. Returns the node's place.
static int BuildNode(Builder *b, std::vector<BinaryNode> *part, int begin, int end,
                     const NodeBounds *bounds, int depth) {
    int place = (int)part->size();
    part->emplace_back();
    BinaryNode node = {ToBox(&bounds->box), HalfArea(&bounds->box), 0, begin, 0, 0};
    NodeBounds side[2];
    int middle = end - begin <= kLanes ? -1
                 : b->wide             ? PartitionWide(b->items, begin, end, bounds, depth, side)
                                       : PartitionPlain(b->items, begin, end, bounds, depth, side);
    if (middle < 0) {
        std::sort(b->items + begin, b->items + end,
                  [](const BuildItem &x, const BuildItem &y) { return x.index < y.index; });
        node.count = end - begin;
    } else {
        Task second = {middle, end, depth + 1, side[1]};
        node.second = end - middle >= kTaskMin ? -1 - AddTask(b, &second) : 0; // (before the
        BuildNode(b, part, begin, middle, &side[0], depth + 1);                // first child)
        if (node.second == 0)
            node.second = BuildNode(b, part, middle, end, &side[1], depth + 1);
    }
    (*part)[place] = node;
    return place;
}

// One thread's share of the build: tasks, until none is left or being done.
static void BuildTasks(Builder *b) {
    std::unique_lock<std::mutex> hold(b->lock);
    for (;;) {
        b->wake.wait(hold, [b] { return b->next < (int)b->tasks.size() || b->unfinished == 0; });
        if (b->next == (int)b->tasks.size())
            return;
        int id = b->next++;
        Task task = b->tasks[id];
        std::vector<BinaryNode> *part = &b->parts[id];
        hold.unlock();
        part->reserve((task.end - task.begin) / 2 + 1); // (most trees have fewer nodes)
        BuildNode(b, part, task.begin, task.end, &task.bounds, task.depth);
        hold.lock();
        if (--b->unfinished == 0)
            b->wake.notify_all();
    }
}

// A task done that was not taken from the list (the items, before the root's task is made).
static void FinishTask(Builder *b) {
    std::lock_guard<std::mutex> hold(b->lock);
    if (--b->unfinished == 0)
        b->wake.notify_all();
}

// A node of the whole tree: its part (task) and its place there.
struct NodeRef {
    int task, place;
};

static BinaryNode *At(Builder *b, NodeRef r) { return &b->parts[r.task][r.place]; }

static NodeRef Second(const BinaryNode *node, NodeRef r) {
    return node->second >= 0 ? NodeRef{r.task, node->second} : NodeRef{-1 - node->second, 0};
}

// Numbers the blocks of the leaves below `r` from `*next` on, in depth-first order (the order
// of the blocks in the layout), and lists the leaves.
static void NumberLeaves(Builder *b, NodeRef r, int *next, std::vector<NodeRef> *leaves) {
    for (;;) {
        BinaryNode *node = At(b, r);
        if (node->count > 0) {
            node->block = *next;
            *next += Blocks(node->count);
            leaves->push_back(r);
            return;
        }
        NumberLeaves(b, {r.task, r.place + 1}, next, leaves);
        r = Second(node, r);
    }
}

// The four-wide node over binary node `top`'s subtree (Embree's BVH4, made from a binary tree as
// Wald, Benthin & Boulos 2008 do): it takes the two children, then opens the inner child of
// largest area, until it has four or only leaves. Returns its place.
static int Collapse(Builder *b, NodeRef top, SceneLayout *layout) {
    NodeRef kids[kWidth] = {top};
    int count = 1;
    if (At(b, top)->count == 0)
        kids[0] = {top.task, top.place + 1}, kids[1] = Second(At(b, top), top), count = 2;
    while (count < kWidth) {
        int open = -1;
        for (int k = 0; k < count; k++)
            if (At(b, kids[k])->count == 0 &&
                (open < 0 || At(b, kids[k])->area > At(b, kids[open])->area))
                open = k;
        if (open < 0)
            break;
        NodeRef inner = kids[open];
        for (int k = count++; k > open + 1; k--)
            kids[k] = kids[k - 1];
        kids[open] = {inner.task, inner.place + 1}, kids[open + 1] = Second(At(b, inner), inner);
    }
    int place = (int)layout->nodes.size();
    layout->nodes.emplace_back();
    BvhNode node = {};
    for (int k = 0; k < kWidth; k++) {
        node.blocks[k] = -1; // no child
        if (k >= count)
            continue;
        const BinaryNode *kid = At(b, kids[k]);
        for (int axis = 0; axis < 3; axis++)
            node.lo[axis][k] = kid->box.lo[axis], node.hi[axis][k] = kid->box.hi[axis];
        node.size[k] = kid->box.size;
        node.blocks[k] = Blocks(kid->count);
        node.child[k] = kid->count > 0 ? kid->block : Collapse(b, kids[k], layout);
    }
    layout->nodes[place] = node;
    return place;
}

// The blocks of leaves[first, last), each at its number.
static void FillLeaves(Builder *b, const std::vector<Triangle> &triangles,
                       const std::vector<NodeRef> &leaves, int first, int last,
                       SceneLayout *layout) {
    int index[kLanes];
    for (int l = first; l < last; l++) {
        const BinaryNode *leaf = At(b, leaves[l]);
        for (int i = 0; i < leaf->count; i += kLanes) {
            int lanes = std::min(kLanes, leaf->count - i);
            for (int lane = 0; lane < lanes; lane++)
                index[lane] = b->items[leaf->first + i + lane].index;
            FillBlock(triangles, index, lanes, &layout->blocks[leaf->block + i / kLanes]);
        }
    }
}

// Below this many triangles the build runs on one thread: starting another costs more.
const int kThreadMin = 4096;

// The set-ups (plane.cpp) of triangles [first, last), in scene order.
static void SetUpRange(const std::vector<Triangle> &triangles, size_t first, size_t last,
                       SceneLayout *layout) {
    for (size_t i = first; i < last; i++)
        SetUpTriangle(&triangles[i], &layout->setUps[i]);
}

// The second thread runs its share of a step here (a named function, so that a profile can
// find it).
template <typename Step> static void Help(const Step *step) { (*step)(); }

// Runs `first` on this thread and `second` on another, when `threads`, and returns when both
// are done; else one after the other.
template <typename First, typename Second>
static void RunBoth(bool threads, const First &first, const Second &second) {
    if (!threads) {
        first(), second();
        return;
    }
    std::thread helper(Help<Second>, &second);
    first();
    helper.join();
}

// The build items of triangles [first, last), and their bounds. The box is TriangleBox's, lane
// by lane: its least and most of three, in its order (so that of -0 and +0 the same one wins),
// and a triangle with a corner that is not finite gets the infinite box; the centre is
// lo / 2 + hi / 2, halves first, as (lo + hi) / 2 could overflow, and 0 for the infinite box.
template <bool kWide>
static RT_INLINE void MakeItems(const Triangle *triangles, int first, int last, BuildItem *items,
                                NodeBounds *bounds) {
    Quad4 half, infinity;
    Splat(&half, real(0.5)), Splat(&infinity, kInfinity);
    for (int i = first; i < last; i++) {
        const Triangle *t = &triangles[i];
        Quad4 a, b, c = {t->c.x, t->c.y, t->c.z, t->c.z}; // (a and b: the next number is lane 3)
        Load(&a, &t->a.x), Load(&b, &t->b.x);
        Quad4 lo = a < b ? a : b, hi = a > b ? a : b;
        lo = lo < c ? lo : c, hi = hi > c ? hi : c;
        Quad4 centre = lo * half + hi * half, finite = (a - a) + (b - b) + (c - c);
        if (!(finite[0] == 0 && finite[1] == 0 && finite[2] == 0 && finite[3] == 0))
            lo = -infinity, hi = infinity, Splat(&centre, 0);
        Store(items[i].lo, &lo), Store(items[i].hi, &hi), Store(items[i].centre, &centre);
        items[i].index = i, items[i].zero = 0;
        GrowBy(&bounds->box, &lo, &hi), GrowPoint(&bounds->centres, &centre);
    }
}
static void MakeItemsPlain(const Triangle *triangles, int first, int last, BuildItem *items,
                           NodeBounds *bounds) {
    MakeItems<false>(triangles, first, last, items, bounds);
}
RT_AVX2 static void MakeItemsWide(const Triangle *triangles, int first, int last, BuildItem *items,
                                  NodeBounds *bounds) {
    MakeItems<true>(triangles, first, last, items, bounds);
}

static void BuildTree(const std::vector<Triangle> &triangles, SceneLayout *layout) {
    int n = (int)triangles.size();
    bool threads = n >= kThreadMin && std::thread::hardware_concurrency() > 1;
    bool wide = KernelCanBeWide();
    std::unique_ptr<BuildItem[]> items(new BuildItem[n]);
    Task root = {0, n, 0, {EmptyBounds(), EmptyBounds()}};
    Builder b;
    b.items = items.get(), b.wide = wide, b.next = 0;
    b.unfinished = 1; // the items, until the root's task is made
    // New memory costs most where it is first written (a page fault each 4 KB): one thread
    // writes the set-ups and the blocks while the other starts the tree
    RunBoth(
        threads,
        [&] {
            (wide ? MakeItemsWide : MakeItemsPlain)(triangles.data(), 0, n, items.get(),
                                                    &root.bounds);
            AddTask(&b, &root);
            FinishTask(&b);
            BuildTasks(&b);
        },
        [&] {
            layout->setUps.resize(n);
            SetUpRange(triangles, 0, n, layout);
            layout->blocks.resize(Blocks(n) + Blocks(n) / 16); // most trees need fewer
            BuildTasks(&b);
        });
    std::vector<NodeRef> leaves;
    int blocks = 0;
    NumberLeaves(&b, {0, 0}, &blocks, &leaves);
    layout->blocks.resize(blocks);
    RunBoth(
        threads, [&] { FillLeaves(&b, triangles, leaves, 0, (int)leaves.size(), layout); },
        [&] {
            layout->nodes.reserve(leaves.size()); // at most a node per inner binary node
            Collapse(&b, {0, 0}, layout);
        });
}

void CommitScene(Scene *scene, LayoutChoice choice) {
    SceneLayout layout;
    const std::vector<Triangle> &triangles = scene->triangles;
    int n = (int)triangles.size();
    bool tree = choice == LAYOUT_BVH || (choice == LAYOUT_AUTO && (size_t)n >= kBvhMinTriangles);
    if (tree && n > 0) {
        BuildTree(triangles, &layout);
    } else {
        std::vector<int> index(n);
        for (int i = 0; i < n; i++)
            index[i] = i;
        AppendBlocks(triangles, index.data(), n, &layout);
        layout.setUps.resize(n);
        SetUpRange(triangles, 0, n, &layout);
    }
    layout.triangleCount = triangles.size();
    layout.committed = true;
    layout.wide = KernelCanBeWide();
    scene->layout = std::move(layout);
}
