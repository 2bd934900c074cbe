// build.cpp -- where the BVH build splits a node's triangles (commit.cpp builds the tree).
//
// CommitScene builds its hierarchy top down, and for each node asks SplitNode where to split it:
// by the surface area heuristic over binned centroids (Wald, "On fast construction of SAH-based
// bounding volume hierarchies", 2007; pbrt-v4 §7.3). One pass bins the centroids on all three
// axes at once, each bin keeping its triangles' count and the union of their boxes; a sweep
// over each axis's bins then prices every boundary, and the cheapest wins, or a leaf. The boxes
// are vectors of four numbers (GCC/Clang vector extensions, as in kernel_blocks.h), and with AVX2
// (the kernel's dispatch) one vector is one instruction: min, max and comparison are exact, so
// every box has the bits of TriangleBox's, and the tree is the same on any machine.
#include "fast.h"
#include "lanes.h"

#include <algorithm>
#include <cstddef>
#include <cstring>

// The surface area heuristic's bins per axis: 16 find splits within a few per cent of the best
// (Wald 2007) at a fraction of the cost of trying every triangle.
const int kBins = 16;

// Four numbers at once: x, y, z and a fourth lane that is not used (Bounds, BuildItem). Vectors
// are passed by pointer, as in kernel_blocks.h: a 32-byte vector is passed differently with AVX.
RT_LANES(Quad4, real, 4);
RT_LANES(Int4, int, 4);
RT_LANES(UInt4, unsigned, 4);

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
    lo = Select(*otherLo < lo, *otherLo, lo), hi = Select(*otherHi > hi, *otherHi, hi);
    Store(b->lo, &lo), Store(b->hi, &hi);
}
static RT_INLINE void Grow(Bounds *b, const Bounds *other) {
    Quad4 lo, hi;
    Load(&lo, other->lo), Load(&hi, other->hi);
    GrowBy(b, &lo, &hi);
}
static RT_INLINE void GrowPoint(Bounds *b, const Quad4 *point) { GrowBy(b, point, point); }

// Half the surface area: the chance that a ray that meets a box meets a box inside it is the
// ratio of their areas (for rays in all directions; the heuristic's premise). A box that holds a
// non-finite triangle has infinite area: a side that is infinite makes a product infinite, or
// 0 * infinity, NaN, and either way the answer is kInfinity.
// (RawHalfArea leaves the NaN: where a cost only competes, BestSplit, a NaN loses as the
// infinity would.)
// (The three products at once, d times d turned by one lane; then summed in the written order.)
static RT_INLINE real RawHalfArea(const Bounds *b) {
    Quad4 lo, hi;
    Load(&lo, b->lo), Load(&hi, b->hi);
    Quad4 d = hi - lo, p = d * Quad4{d[1], d[2], d[0], d[3]};
    return p[0] + p[1] + p[2]; // d[0] * d[1] + d[1] * d[2] + d[2] * d[0]
}
static RT_INLINE real HalfArea(const Bounds *b) {
    real area = RawHalfArea(b);
    return area == area ? area : kInfinity;
}

static_assert(offsetof(BuildItem, centre) + sizeof(Quad4) <= sizeof(BuildItem), "a vector past");

static RT_INLINE void GrowItem(Bounds *b, const BuildItem *item) {
    Quad4 lo, hi;
    Load(&lo, item->lo), Load(&hi, item->hi);
    GrowBy(b, &lo, &hi);
}
// The centre as a vector, its fourth lane 0. (That lane would be the index's bits, a subnormal
// number, which a processor may take a hundred cycles to compute with.)
static RT_INLINE void LoadCentre(const BuildItem *item, Quad4 *c) {
    typedef decltype(*c < *c) Mask4;
    Mask4 keep = {-1, -1, -1, 0};
    Load(c, item->centre);
    *c = Bitcast<Quad4>(Bitcast<Mask4>(*c) & keep);
}
static RT_INLINE void GrowCentre(Bounds *b, const BuildItem *item) {
    Quad4 c;
    LoadCentre(item, &c);
    GrowPoint(b, &c);
}

// The bins of a node's centroids on all three axes, filled in one pass (Wald 2007): per
// bin, how many and the union of their boxes (together, so that one offset finds both), and
// per axis a bit for each bin that holds an item. An axis whose centroids do not spread has
// scale 0.
// (A bin takes the room of two boxes, a power of two bytes: its offset is then a shift, not a
// multiplication.)
struct alignas(2 * sizeof(Bounds)) Bin {
    Bounds box;
    int count;
};
struct Bins {
    Bin bin[3][kBins];
    unsigned full[3];     // bit k: bin k holds an item
    real lo[4], scale[4]; // per axis (the fourth is 0)
};
static_assert(kBins <= 32, "a bin's bit in an unsigned");

// An item's bins, the three found at once: the whole part of f = (c - lo) scale, at most the
// last. f is first cut to the last bin's number (a NaN, which compares false, becomes it too),
// so that its conversion to int is always defined; f is never below 0 (c >= lo).
static RT_INLINE UInt4 BinsOf(const BuildItem *item, const Quad4 *lo, const Quad4 *scale) {
    Quad4 centre, last;
    LoadCentre(item, &centre);
    Splat(&last, kBins - 1);
    Quad4 f = (centre - *lo) * *scale;
    return Bitcast<UInt4>(Convert<Int4>(Select(f < last, f, last)));
}

// The item's box added to its bins (`k`, BinsOf), each found by the byte offset of its place in
// the bins of all three axes (axis times kBins on).
static RT_INLINE void AddItemAt(const BuildItem *item, UInt4 k, Bins *bins) {
    Quad4 itemLo, itemHi; // (read once: the bins' stores could alias them)
    Load(&itemLo, item->lo), Load(&itemHi, item->hi);
    UInt4 first = {0, kBins, 2 * kBins, 0};
    UInt4 offset = (k + first) * (unsigned)sizeof(Bin);
    char *start = (char *)bins->bin;
    for (int axis = 0; axis < 3; axis++) {
        Bin *bin = (Bin *)(start + offset[axis]);
        bin->count++;
        GrowBy(&bin->box, &itemLo, &itemHi);
    }
}
static RT_INLINE void AddItem(const BuildItem *item, const Quad4 *lo, const Quad4 *scale,
                              Bins *bins) {
    AddItemAt(item, BinsOf(item, lo, scale), bins);
}

static RT_INLINE void ClearBins(Bins *bins) {
    for (int axis = 0; axis < 3; axis++)
        for (int k = 0; k < kBins; k++)
            bins->bin[axis][k] = {EmptyBounds(), 0};
}

// Every bin cleared, the items added, then each axis's full bins noted.
static RT_INLINE void FillAllBins(const BuildItem *items, int n, const Quad4 *lo,
                                  const Quad4 *scale, Bins *bins) {
    ClearBins(bins);
    for (int i = 0; i < n; i++)
        AddItem(&items[i], lo, scale, bins);
    for (int axis = 0; axis < 3; axis++) {
        bins->full[axis] = 0;
        for (int k = 0; k < kBins; k++)
            bins->full[axis] |= (unsigned)(bins->bin[axis][k].count > 0) << k;
    }
}

// Below this many items a node's bins are found first, and only the full ones cleared: a small
// node fills few of its 48 bins, and clearing them all would cost more than filling them.
const int kFewItems = 16;

static RT_INLINE void FillFewBins(const BuildItem *items, int n, const Quad4 *lo,
                                  const Quad4 *scale, Bins *bins) {
    UInt4 k[kFewItems], full = {0, 0, 0, 0}, one = {1, 1, 1, 1};
    for (int i = 0; i < n; i++)
        k[i] = BinsOf(&items[i], lo, scale), full |= one << k[i];
    for (int axis = 0; axis < 3; axis++) {
        bins->full[axis] = full[axis];
        for (unsigned bits = full[axis]; bits != 0; bits &= bits - 1)
            bins->bin[axis][LowestBit(bits)] = {EmptyBounds(), 0};
    }
    for (int i = 0; i < n; i++)
        AddItemAt(&items[i], k[i], bins);
}

static RT_INLINE void FillBins(const BuildItem *items, int n, Bins *bins) {
    Quad4 lo, scale;
    Load(&lo, bins->lo), Load(&scale, bins->scale);
    if (n < kFewItems)
        FillFewBins(items, n, &lo, &scale, bins);
    else
        FillAllBins(items, n, &lo, &scale, bins);
}

// A split of a node's items: bins below `bin` of `axis` go left; what it costs.
struct Split {
    real cost, sides; // sides: the sum of the two sides' areas times blocks, cost's numerator
    int axis, bin;
};

// The best boundary between the bins of `axis` (bins below it go left), and its cost in block
// tests: 1 for the node, plus for each side the chance that a ray meeting the node meets that
// side times that side's blocks. Only boundaries right after a full bin are tried: one after an
// empty bin splits the same way, and the first of those is the one a sweep over all finds.
static RT_INLINE void BestSplit(const Bins *bins, int axis, real nodeArea, const LeafShape *leaves,
                                Split *best) {
    int shift = leaves->shift;
    const Bin *bin = bins->bin[axis];
    int full[kBins], m = 0;
    for (unsigned bits = bins->full[axis]; bits != 0; bits &= bits - 1)
        full[m++] = LowestBit(bits);
    if (m < 2)
        return;
    real rightCost[kBins]; // area times blocks
    Bounds right = bin[full[m - 1]].box;
    int rightCount = bin[full[m - 1]].count;
    rightCost[m - 1] = RawHalfArea(&right) * BlocksOf(rightCount, shift);
    for (int j = m - 2; j > 0; j--) { // everything in full bins j and above
        Grow(&right, &bin[full[j]].box);
        rightCount += bin[full[j]].count;
        rightCost[j] = RawHalfArea(&right) * BlocksOf(rightCount, shift);
    }
    Bounds left = bin[full[0]].box;
    int leftCount = bin[full[0]].count;
    for (int j = 1; j < m; j++) {
        if (j > 1)
            Grow(&left, &bin[full[j - 1]].box), leftCount += bin[full[j - 1]].count;
        real sides = RawHalfArea(&left) * BlocksOf(leftCount, shift) + rightCost[j];
        if (!(sides < best->sides)) // (rounding is monotonic: then the cost is no less either)
            continue;
        real cost = leaves->nodeCost + sides / nodeArea; // (a division only where it may fall)
        if (cost < best->cost)
            *best = {cost, sides, axis, full[j - 1] + 1};
    }
}

// The boxes of the two sides of a split: the unions of their bins.
static RT_INLINE void SideBoxes(const Bins *bins, const Split *split, NodeBounds side[2]) {
    side[0].box = side[1].box = EmptyBounds();
    for (unsigned bits = bins->full[split->axis]; bits != 0; bits &= bits - 1) {
        int k = LowestBit(bits);
        Grow(&side[k >= split->bin].box, &bins->bin[split->axis][k].box);
    }
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

// Where the bins of each axis lie: from the least centre, kBins to the centres' extent. False if
// on no axis the centres spread (a spread of 1e-308 would make the scale infinite: no spread).
static RT_INLINE bool PlaceBins(const NodeBounds *node, Bins *bins) {
    bool spread = false;
    for (int k = 0; k < 3; k++) {
        real extent = node->centres.hi[k] - node->centres.lo[k];
        bool usable = extent > 0 && std::isfinite(extent) && std::isfinite(kBins / extent);
        bins->lo[k] = usable ? node->centres.lo[k] : 0;
        bins->scale[k] = usable ? kBins / extent : 0;
        spread = spread || usable;
    }
    bins->lo[3] = bins->scale[3] = 0;
    return spread;
}

// SplitNode (fast.h), compiled twice: with AVX2 a box is two vectors, not four halves.
static RT_INLINE int SplitItems(BuildItem *items, int begin, int end, const NodeBounds *node,
                                bool heuristic, const LeafShape *leaves, NodeBounds side[2]) {
    int n = end - begin;
    Bins bins;
    Split best = {kInfinity, kInfinity, 0, 0};
    // Items whose centres all coincide (copies of one shape) cannot be told apart by any split:
    // each side would have the node's own box, and a ray would walk both. They stay one leaf, which
    // costs what the list does.
    const Bounds *c = &node->centres;
    if (c->lo[0] == c->hi[0] && c->lo[1] == c->hi[1] && c->lo[2] == c->hi[2])
        return -1;
    if (heuristic && PlaceBins(node, &bins)) {
        FillBins(items + begin, n, &bins);
        real area = HalfArea(&node->box);
        for (int k = 0; k < 3; k++)
            if (bins.scale[k] > 0)
                BestSplit(&bins, k, area, leaves, &best);
    }
    if (best.cost < kInfinity) {
        int blocks = BlocksOf(n, leaves->shift);
        if (best.cost >= blocks && blocks <= leaves->maxBlocks)
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
static int SplitPlain(BuildItem *items, int begin, int end, const NodeBounds *node, bool heuristic,
                      const LeafShape *leaves, NodeBounds side[2]) {
    return SplitItems(items, begin, end, node, heuristic, leaves, side);
}
RT_AVX2 static int SplitVectors(BuildItem *items, int begin, int end, const NodeBounds *node,
                                bool heuristic, const LeafShape *leaves, NodeBounds side[2]) {
    return SplitItems(items, begin, end, node, heuristic, leaves, side);
}

int SplitNode(BuildItem *items, int begin, int end, const NodeBounds *node, bool heuristic,
              const LeafShape *leaves, bool vectors, NodeBounds side[2]) {
    return (vectors ? SplitVectors : SplitPlain)(items, begin, end, node, heuristic, leaves, side);
}

// MakeBuildItems (fast.h), compiled twice. The box is TriangleBox's, lane by lane: its least and
// most of three in its order (so that of -0 and +0 the same one wins), and for a triangle with a
// corner that is not finite the infinite box; the centre is lo / 2 + hi / 2, halves first, as
// (lo + hi) / 2 could overflow, and 0 for the infinite box.
static RT_INLINE void MakeItems(const Triangle *triangles, int first, int last, BuildItem *items,
                                NodeBounds *bounds) {
    *bounds = {EmptyBounds(), EmptyBounds()};
    Quad4 half, infinity;
    Splat(&half, real(0.5)), Splat(&infinity, kInfinity);
    for (int i = first; i < last; i++) {
        const Triangle *t = &triangles[i];
        Quad4 a, b, c = {t->c.x, t->c.y, t->c.z, t->c.z}; // (a, b: the 4th lane is what follows)
        Load(&a, &t->a.x), Load(&b, &t->b.x);
        Quad4 lo = Select(a < b, a, b), hi = Select(a > b, a, b);
        lo = Select(lo < c, lo, c), hi = Select(hi > c, hi, c);
        Quad4 centre = lo * half + hi * half, finite = (a - a) + (b - b) + (c - c);
        if (!(finite[0] == 0 && finite[1] == 0 && finite[2] == 0 && finite[3] == 0))
            lo = -infinity, hi = infinity, Splat(&centre, 0);
        // (each vector's fourth lane lands on the next field, which the next store writes; the
        // centre's on the index and the padding after it, all 0 until the index is written)
        centre[3] = 0;
        Store(items[i].lo, &lo), Store(items[i].hi, &hi), Store(items[i].centre, &centre);
        items[i].index = i;
        GrowBy(&bounds->box, &lo, &hi), GrowPoint(&bounds->centres, &centre);
    }
}
static void MakeItemsPlain(const Triangle *triangles, int first, int last, BuildItem *items,
                           NodeBounds *bounds) {
    MakeItems(triangles, first, last, items, bounds);
}
RT_AVX2 static void MakeItemsVectors(const Triangle *triangles, int first, int last,
                                     BuildItem *items, NodeBounds *bounds) {
    MakeItems(triangles, first, last, items, bounds);
}

void MakeBuildItems(const Triangle *triangles, int first, int last, bool vectors, BuildItem *items,
                    NodeBounds *bounds) {
    (vectors ? MakeItemsVectors : MakeItemsPlain)(triangles, first, last, items, bounds);
}

void BoundsBox(const Bounds *b, Box *out, real *halfArea) {
    Box box = {{b->lo[0], b->lo[1], b->lo[2]}, {b->hi[0], b->hi[1], b->hi[2]}, 0};
    real lo = MaxComponent({box.lo[0], box.lo[1], box.lo[2]});
    real hi = MaxComponent({box.hi[0], box.hi[1], box.hi[2]});
    box.size = lo > hi ? lo : hi;
    *out = box, *halfArea = HalfArea(b);
}
