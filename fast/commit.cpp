// fast/commit.cpp -- the committed scene: the shapes in the layout the fast search reads.
//
// A scene is written, read and explained as the handouts' structs. Once per render, CommitScene
// (after Embree's rtcCommitScene) copies the triangles, and the spheres, into blocks of kLanes,
// coordinate by coordinate, for the kernel (kernel.cpp) to test a block at a time (the spheres in
// commit_spheres.cpp); and when the scene has enough triangles that it pays (kBvhMinTriangles),
// it builds a bounding
// volume hierarchy over them: a binary tree, top down, each node split where build.cpp says (the
// surface area heuristic over binned centroids: Wald, "On fast construction of SAH-based bounding
// volume hierarchies", 2007; pbrt-v4 §7.3), then collapsed to four children a node. Large
// subtrees are tasks that a second thread shares; each depends only on its triangles, so the tree
// is the same whoever builds what. Nothing here changes an answer: the kernel returns the plain
// loop's bits.
#include "fast.h"

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <deque>
#include <memory>
#include <mutex>
#include <new>
#include <system_error>
#include <thread>

// Below this many triangles the blocks are one list: a ray then tests them all, which is
// cheaper than walking a tree for the assignment's five triangles. `make bench` (its mesh table,
// docs/speed.md) shows the tree winning from about this size on.
const size_t kBvhMinTriangles = 32;

// Below this depth the surface area heuristic splits; deeper (a heuristic that keeps splitting
// one triangle off a long list) the median does, which halves each time: the traversal stack
// (kernel_walk.h, kMaxDepth) then holds a tree of any size rt can read.
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

// A node of the binary tree the heuristic builds, before it is collapsed to four children a
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
    int middle = end - begin <= kLanes ? -1
                                       : SplitNode(b->items, begin, end, bounds,
                                                   depth < kMaxSahDepth, b->vectors, side);
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

// The children of a four-wide node over binary node `top` (Embree's BVH4, made from a binary
// tree as Wald, Benthin & Boulos 2008 do): its two children, then the inner child of largest
// area opened, until there are four or only leaves. Returns how many.
static int FourKids(Builder *b, NodeRef top, NodeRef kids[kChildren]) {
    int count = 1;
    kids[0] = top;
    if (At(b, top)->count == 0)
        kids[0] = {top.task, top.place + 1}, kids[1] = Second(At(b, top), top), count = 2;
    while (count < kChildren) {
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
    return count;
}

// The four-wide subtree over binary node `top`'s, depth-first, its leaves' blocks numbered from
// `*next` on: the order NumberLeaves numbers them in, as each node's kids keep the binary
// tree's order (FourKids), so Collapse needs no numbers from it. Returns the top node's place.
static int Collapse(Builder *b, NodeRef top, int *next, SceneLayout *layout) {
    NodeRef kids[kChildren];
    int count = FourKids(b, top, kids);
    int place = (int)layout->nodes.size();
    layout->nodes.emplace_back();
    BvhNode node = {};
    for (int k = 0; k < kChildren; k++) {
        node.blocks[k] = -1; // no child
        if (k >= count)
            continue;
        const BinaryNode *kid = At(b, kids[k]);
        SetChildBox(&node, k, &kid->box);
        node.blocks[k] = Blocks(kid->count);
        if (kid->count > 0)
            node.child[k] = *next, *next += Blocks(kid->count);
        else
            node.child[k] = Collapse(b, kids[k], next, layout);
    }
    layout->nodes[place] = node;
    return place;
}

// The blocks of leaves[first, last), each at its number, into `blocks`. (They may lie over the
// items, ItemsInBlocks: once the tree is built, only the leaves' orders are read.)
static void FillLeaves(Builder *b, const std::vector<Triangle> &triangles,
                       const std::vector<NodeRef> &leaves, size_t first, size_t last,
                       TriangleBlock *blocks) {
    for (size_t l = first; l < last; l++) {
        const BinaryNode *leaf = At(b, leaves[l]);
        for (int i = 0; i < leaf->count; i += kLanes) {
            TriangleBlock *block = new (&blocks[leaf->block + i / kLanes]) TriangleBlock;
            FillBlock(triangles, b->order + leaf->first + i, std::min(kLanes, leaf->count - i),
                      block);
        }
    }
}

// The items, made in the memory of the blocks, which are written only once the tree is built:
// new memory costs most where it is first written (a page fault each 4 KB), and this way the
// same pages serve both. The blocks are as many as the tree will likely need (its leaves leave
// some lanes empty: a sixteenth more than Blocks(n) is room enough for the meshes of
// tools/make_mesh), and enough to hold the items.
static BuildItem *ItemsInBlocks(int n, SceneLayout *layout) {
    size_t items =
        ((size_t)n * sizeof(BuildItem) + sizeof(TriangleBlock) - 1) / sizeof(TriangleBlock);
    layout->blocks.resize(std::max(items, (size_t)(Blocks(n) + Blocks(n) / 16)));
    BuildItem *first = reinterpret_cast<BuildItem *>(layout->blocks.data());
    for (int i = 0; i < n; i++)
        new (&first[i]) BuildItem;
    return first;
}

// The leaves a thread fills at a time: a small share of a large mesh's leaves, so that the two
// threads finish close together, and the shared counter is touched once a few hundred leaves.
const size_t kLeafShare = 256;

// Below this many triangles the build runs on one thread: starting a thread would cost a good
// part of what it could save.
const int kThreadMin = 4096;

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

// Once the tree is built: the leaves' blocks numbered and filled, and the four-wide tree.
static void NumberAndCollapse(Builder *b, const std::vector<Triangle> &triangles, bool threads,
                              SceneLayout *layout) {
    // One thread numbers the leaves and then fills their blocks, a share of leaves at a time,
    // while the other collapses the tree and then helps to fill them. (Run one after the other,
    // the leaves are ready before the collapse starts.)
    std::vector<NodeRef> leaves;
    std::atomic<bool> ready(false); // the leaves listed and the blocks sized
    std::atomic<size_t> next(0);
    auto fill = [&] {
        for (size_t first; (first = next.fetch_add(kLeafShare)) < leaves.size();)
            FillLeaves(b, triangles, leaves, first, std::min(first + kLeafShare, leaves.size()),
                       layout->blocks.data());
    };
    auto number = [&] {
        int blocks = 0;
        NumberLeaves(b, {0, 0}, &blocks, &leaves);
        layout->blocks.resize(blocks); // (the items are no longer needed)
        ready.store(true, std::memory_order_release);
        fill();
    };
    size_t binary = 0; // the binary tree's nodes, of which (binary + 1) / 2 are leaves
    for (const std::vector<BinaryNode> &part : b->parts)
        binary += part.size();
    RunBoth(threads, number, [&] {
        layout->nodes.reserve((binary + 1) / 2); // at most a node per inner binary node
        int blocks = 0;
        Collapse(b, {0, 0}, &blocks, layout);
        while (!ready.load(std::memory_order_acquire))
            std::this_thread::yield();
        fill();
    });
}

static void BuildTree(const std::vector<Triangle> &triangles, int most, SceneLayout *layout) {
    int n = (int)triangles.size();
    bool threads = most > 1 && n >= kThreadMin && std::thread::hardware_concurrency() > 1;
    bool vectors = KernelHasVectors();
    Task root = {0, n, 0, {}};
    std::unique_ptr<int[]> order(new int[n]);
    Builder b;
    b.items = nullptr, b.order = order.get(), b.vectors = vectors, b.next = 0;
    b.unfinished = 1; // the items, until the root's task is made
    // One thread makes the items (in the blocks' memory) and starts the tree while the other
    // writes the set-ups
    RunBoth(
        threads,
        [&] {
            b.items = ItemsInBlocks(n, layout);
            MakeBuildItems(triangles.data(), 0, n, vectors, b.items, &root.bounds);
            AddTask(&b, &root);
            FinishTask(&b);
            BuildTasks(&b);
        },
        [&] {
            SetUpAll(triangles, layout);
            BuildTasks(&b);
        });
    NumberAndCollapse(&b, triangles, threads, layout);
}

void CommitScene(Scene *scene, LayoutChoice choice, int threads, SceneLayout *layout) {
    layout->blocks.clear(), layout->nodes.clear(), layout->setUps.clear();
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
    layout->accelerator = {layout, SearchLayout, SearchEyeRays};
    scene->accelerator = &layout->accelerator;
}
