// fast/commit_tree.cpp -- the triangles' BVH (CommitScene): built top down as a binary tree, each
// node split where build.cpp says (the surface area heuristic over binned centroids: Wald, "On
// fast construction of SAH-based bounding volume hierarchies", 2007; pbrt-v4 §7.3), then
// collapsed to eight children a node (Wald, Benthin & Boulos 2008), whose boxes, and the leaves'
// corners, are stored in float (WideNode, WideBlock: fast.h says why that culls nothing the exact
// test would keep). Large subtrees are tasks that a second thread shares; each depends only on
// its triangles, so the tree is the same whoever builds what.
#include "fast.h"

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstring>
#include <deque>
#include <memory>
#include <mutex>
#include <new>
#include <system_error>
#include <thread>

// Below this depth the surface area heuristic splits; deeper (a heuristic that keeps splitting
// one triangle off a long list) the median does, which halves each time: the traversal stack
// (kernel_wide.h, kMaxWideDepth) then holds a tree of any size rt can read.
const int kMaxSahDepth = 48;

// The leaves: blocks of kWide triangles, at most kMaxWideLeafBlocks a leaf.
const LeafShape kTriangleLeaves = {3, 1, 1};
static_assert(1 << 3 == kWide, "kTriangleLeaves' shift is kWide's");

// A node of the binary tree the heuristic builds, before it is collapsed to eight children a
// node (Collapse). The tree is built in parts, one per task (BuildTasks); an inner node's first
// child follows it in its part, its second is elsewhere in the part or the root of another.
struct BinaryNode {
    Box box;
    real area;  // half its surface area (BoundsBox)
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
    int *order;   // a leaf's triangles' places, sorted, where its items are (FillLeaves reads them)
    bool vectors; // binning with AVX2 (KernelHasVectors)
    std::mutex lock;
    std::condition_variable wake;
    std::vector<Task> tasks;                   // by id, in the order they were made
    std::deque<std::vector<BinaryNode>> parts; // by task id (a deque: a part stays put)
    int next;                                  // the first task not yet taken
    int unfinished;                            // tasks made and not yet done
};

// A subtree of at least this many triangles is left to any thread (a new task) rather than
// built at once by the thread that splits it off: large enough that a task costs little
// beside its work, small enough that the two threads finish about together (the build's time
// changes little from half to four times this).
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
// right after it, then its second (or a task for it). Returns the node's place.
static int BuildNode(Builder *b, std::vector<BinaryNode> *part, int begin, int end,
                     const NodeBounds *bounds, int depth) {
    int place = (int)part->size();
    part->emplace_back();
    BinaryNode node = {{}, 0, 0, begin, 0, 0};
    BoundsBox(&bounds->box, &node.box, &node.area);
    NodeBounds side[2];
    int middle = end - begin <= kWide ? -1
                                      : SplitNode(b->items, begin, end, bounds,
                                                  depth < kMaxSahDepth, &kTriangleLeaves,
                                                  b->vectors, side);
    if (middle < 0) {
        node.count = end - begin;
        for (int i = begin; i < end; i++)
            b->order[i] = b->items[i].index;
        std::sort(b->order + begin,
                  b->order + end); // (its triangles keep their order in the scene)
    } else {
        // A large second child is a task made before the first child is built: another thread
        // can take it meanwhile
        bool task = end - middle >= kTaskMin;
        Task second = {middle, end, depth + 1, side[1]};
        node.second = task ? -1 - AddTask(b, &second) : 0;
        BuildNode(b, part, begin, middle, &side[0], depth + 1);
        if (!task)
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
            *next += BlocksOf(node->count, kTriangleLeaves.shift);
            leaves->push_back(r);
            return;
        }
        NumberLeaves(b, {r.task, r.place + 1}, next, leaves);
        r = Second(node, r);
    }
}

// How the collapse spends a wide node's kWide slots (Ylitie, Karras & Laine, "Efficient
// incoherent ray traversal on GPUs through compressed wide BVHs", 2017): for each binary node,
// the least cost of its subtree held in at most j slots, j = 1..kWide, and how. A node in one
// slot is a leaf, or a wide node of its own that pays a visit; in more, its two children share
// them. The cost is the surface area heuristic's: each box's area times what a ray that meets it
// pays there (a visit, or its blocks' tests), which cost about the same.
const float kVisitCost = 1, kBlockCost = 1;
struct Slots {
    float cost[kWide];         // cost[j - 1]: in at most j slots
    unsigned char first[kWide]; // first[j - 1]: the slots its first child takes; 0: one slot
    unsigned char own;          // as a wide node of its own: the slots its first child takes
};

// Each binary node's place among all parts' nodes (Slots are kept by it).
static int Place(const std::vector<int> &offset, NodeRef r) { return offset[r.task] + r.place; }

// The Slots of the subtree of r, children first.
static void PriceSlots(Builder *b, NodeRef r, const std::vector<int> &offset, Slots *slots) {
    const BinaryNode *node = At(b, r);
    Slots *s = &slots[Place(offset, r)];
    if (node->count > 0) {
        float leaf = (float)node->area * kBlockCost * BlocksOf(node->count, kTriangleLeaves.shift);
        for (int j = 0; j < kWide; j++)
            s->cost[j] = leaf, s->first[j] = 0;
        return;
    }
    NodeRef left = {r.task, r.place + 1}, right = Second(node, r);
    PriceSlots(b, left, offset, slots), PriceSlots(b, right, offset, slots);
    const Slots *l = &slots[Place(offset, left)], *h = &slots[Place(offset, right)];
    float shared[kWide + 1];
    unsigned char first[kWide + 1];
    for (int j = 2; j <= kWide; j++) { // j slots shared: k for the first child
        shared[j] = INFINITY, first[j] = 1;
        for (int k = 1; k < j; k++)
            if (l->cost[k - 1] + h->cost[j - k - 1] < shared[j])
                shared[j] = l->cost[k - 1] + h->cost[j - k - 1], first[j] = (unsigned char)k;
    }
    float alone = (float)node->area * kVisitCost + shared[kWide];
    s->cost[0] = alone, s->first[0] = 0, s->own = first[kWide];
    for (int j = 2; j <= kWide; j++) {
        bool share = shared[j] < alone;
        s->cost[j - 1] = share ? shared[j] : alone, s->first[j - 1] = share ? first[j] : 0;
    }
}

// The nodes that fill the slots of node r's subtree, at most j, in the binary tree's order.
static void FillSlots(Builder *b, NodeRef r, int j, const std::vector<int> &offset,
                      const Slots *slots, std::vector<NodeRef> *kids) {
    const BinaryNode *node = At(b, r);
    int first = node->count > 0 ? 0 : slots[Place(offset, r)].first[j - 1];
    if (first == 0)
        return kids->push_back(r);
    FillSlots(b, {r.task, r.place + 1}, first, offset, slots, kids);
    FillSlots(b, Second(node, r), j - first, offset, slots, kids);
}

// The children of the wide node over binary node `top`: its two children's slots as priced.
// (A leaf at the top, a tree of one leaf, is the one child.)
static int WideKids(Builder *b, NodeRef top, const std::vector<int> &offset, const Slots *slots,
                    NodeRef kids[kWide]) {
    const BinaryNode *node = At(b, top);
    if (node->count > 0)
        return kids[0] = top, 1;
    std::vector<NodeRef> list;
    int first = slots[Place(offset, top)].own;
    FillSlots(b, {top.task, top.place + 1}, first, offset, slots, &list);
    FillSlots(b, Second(node, top), kWide - first, offset, slots, &list);
    std::copy(list.begin(), list.end(), kids);
    return (int)list.size();
}

// The wide subtree over binary node `top`'s, depth-first, its leaves' blocks numbered from
// `*next` on: the order NumberLeaves numbers them in, as each node's kids keep the binary
// tree's order (WideKids), so Collapse needs no numbers from it. Returns the top node's place.
static int Collapse(Builder *b, NodeRef top, const std::vector<int> &offset, const Slots *slots,
                    int exponent, int *next, SceneLayout *layout) {
    NodeRef kids[kWide];
    int count = WideKids(b, top, offset, slots, kids);
    int place = (int)layout->wideNodes.size();
    layout->wideNodes.emplace_back();
    WideNode node;
    for (int k = 0; k < kWide; k++) { // missing children: the empty box, which no ray enters
        for (int axis = 0; axis < 3; axis++)
            node.lo[axis][k] = INFINITY, node.hi[axis][k] = -INFINITY;
        node.child[k] = 0;
    }
    for (int k = 0; k < count; k++) {
        const BinaryNode *kid = At(b, kids[k]);
        SetWideChildBox(&node, k, &kid->box, exponent);
        int blocks = BlocksOf(kid->count, kTriangleLeaves.shift);
        if (kid->count > 0)
            node.child[k] = WideLeaf(*next, blocks), *next += blocks;
        else
            node.child[k] = Collapse(b, kids[k], offset, slots, exponent, next, layout);
    }
    layout->wideNodes[place] = node;
    return place;
}

// The blocks of leaves[first, last), each at its number, into `blocks`.
static void FillLeaves(Builder *b, const std::vector<Triangle> &triangles,
                       const std::vector<NodeRef> &leaves, size_t first, size_t last,
                       int exponent, WideBlock *blocks) {
    for (size_t l = first; l < last; l++) {
        const BinaryNode *leaf = At(b, leaves[l]);
        for (int i = 0; i < leaf->count; i += kWide)
            FillWideBlock(triangles, b->order + leaf->first + i, std::min(kWide, leaf->count - i),
                          exponent, &blocks[leaf->block + i / kWide]);
    }
}

// The leaves a thread fills at a time: a small share of a large mesh's leaves, so that the two
// threads finish close together, and the shared counter is touched once a few hundred leaves.
const size_t kLeafShare = 256;

// Below this many triangles the build runs on one thread: starting a thread would cost a good
// part of what it could save.
const int kThreadMin = 4096;

// The second thread runs its share of a step here (a named function, so that a profile can
// find it).
template <typename Step> static void Help(const Step *step) { (*step)(); }

// Runs `first` on this thread and `second` on another, when `threads`, and returns when both
// are done; else, or if the system gives no thread, one after the other. `first` must never
// wait for `second`.
template <typename First, typename Second>
static void RunBoth(bool threads, const First &first, const Second &second) {
    std::thread helper;
    try {
        if (threads)
            helper = std::thread(Help<Second>, &second);
    } catch (const std::exception &) { // no thread to be had (a limit on threads or memory)
    }
    first();
    if (helper.joinable())
        helper.join();
    else // (first never waits for second, so one after the other is safe)
        second();
}

// Once the tree is built: the leaves' blocks numbered and filled, and the wide tree.
static void NumberAndCollapse(Builder *b, const std::vector<Triangle> &triangles, bool threads,
                              int exponent, SceneLayout *layout) {
    // One thread numbers the leaves and then fills their blocks, a share of leaves at a time,
    // while the other collapses the tree and then helps to fill them. (Run one after the other,
    // the leaves are ready before the collapse starts.)
    std::vector<NodeRef> leaves;
    std::atomic<bool> ready(false); // the leaves listed and the blocks sized
    std::atomic<size_t> next(0);
    auto fill = [&] {
        for (size_t first; (first = next.fetch_add(kLeafShare)) < leaves.size();)
            FillLeaves(b, triangles, leaves, first, std::min(first + kLeafShare, leaves.size()),
                       exponent, layout->wideBlocks.data());
    };
    auto number = [&] {
        int blocks = 0;
        NumberLeaves(b, {0, 0}, &blocks, &leaves);
        layout->wideBlocks.resize(blocks);
        ready.store(true, std::memory_order_release);
        fill();
    };
    size_t binary = 0; // the binary tree's nodes, of which (binary + 1) / 2 are leaves
    for (const std::vector<BinaryNode> &part : b->parts)
        binary += part.size();
    RunBoth(threads, number, [&] {
        layout->wideNodes.reserve((binary + 1) / 2 / (kWide - 1) + 1); // about as many as made
        std::vector<int> offset; // each part's first node's place among all
        int places = 0;
        for (const std::vector<BinaryNode> &part : b->parts)
            offset.push_back(places), places += (int)part.size();
        std::unique_ptr<Slots[]> slots(new Slots[places]);
        PriceSlots(b, {0, 0}, offset, slots.get());
        int blocks = 0;
        Collapse(b, {0, 0}, offset, slots.get(), exponent, &blocks, layout);
        while (!ready.load(std::memory_order_acquire))
            std::this_thread::yield();
        fill();
    });
    layout->wideNodes.shrink_to_fit();
}

// The exponent that brings the largest finite coordinate of the scene into [1, 2): that of the
// root's box, unless a triangle that is not finite made it infinite (then the finite ones are
// looked at one by one). 0 for a scene whose every corner is 0 or not finite.
static int WideExponent(const std::vector<Triangle> &triangles, const Bounds *root) {
    real most = 0;
    for (int axis = 0; axis < 3; axis++)
        most = std::max({most, std::fabs(root->lo[axis]), std::fabs(root->hi[axis])});
    if (!std::isfinite(most)) {
        most = 0;
        for (const Triangle &t : triangles)
            if (IsFinite(t.a) && IsFinite(t.b) && IsFinite(t.c))
                most = std::max({most, MaxComponent(t.a), MaxComponent(t.b), MaxComponent(t.c)});
    }
    return most > 0 ? -BinaryExponent(most) : 0;
}

void BuildTree(const std::vector<Triangle> &triangles, int most, SceneLayout *layout) {
    int n = (int)triangles.size();
    bool threads = most > 1 && n >= kThreadMin && std::thread::hardware_concurrency() > 1;
    bool vectors = KernelHasVectors();
    Task root = {0, n, 0, {}};
    std::unique_ptr<int[]> order(new int[n]);
    std::unique_ptr<BuildItem[]> items(new BuildItem[n]);
    Builder b;
    b.items = items.get(), b.order = order.get(), b.vectors = vectors, b.next = 0;
    b.unfinished = 0;
    MakeBuildItems(triangles.data(), 0, n, vectors, b.items, &root.bounds);
    AddTask(&b, &root);
    RunBoth(threads, [&] { BuildTasks(&b); }, [&] { BuildTasks(&b); });
    items.reset(); // (only the leaves' orders are read from here on)
    layout->wideExponent = WideExponent(triangles, &root.bounds.box);
    NumberAndCollapse(&b, triangles, threads, layout->wideExponent, layout);
}
