// robust/plane.cpp -- where a ray meets a triangle's plane: t, the hit point, and their error
// bounds.
//
// The second handout finds a triangle hit in two steps: where the ray meets the triangle's
// plane, then whether that point is inside. rt decides "inside" with the watertight test
// (watertight.cpp) and takes t from the plane, here, with the handout's formula:
//     t = n.(a - o) / n.d,   n = (b - a) x (c - a).
// Why not the watertight test's own t = (U az + V bz + W cz) / det: its edge functions carry an
// error of about u L^2 for a triangle of length L, and det is about L w for its width w, so that
// t is off by about u L^2 / w. In a corridor 1e8 units long this is more than the 1.5 units from
// a ray's origin to the floor, and an honest bound must then throw the hit away: the ray escapes
// through a closed box. The plane's t has errors of the sizes that the hit itself has (|a - o|,
// |t d|), and it is computed in two tiers:
//   1. In double, also in the float build, where products of floats are exact in double. A
//      first-order error bound comes with it. Almost every hit is settled here.
//   2. When that bound cannot tell whether t > 0 (a ray that leaves this very plane), or is wider
//      than kPlainRelativeError (a triangle much longer than the ray's way to it, seen from near
//      its plane), the same formula again in double-double arithmetic, whose error is about u^2
//      of the terms. This is what keeps boxes and floors of any length closed.
#include "robust.h"

#include <algorithm>

static dvec3 Widen(vec3 v) { return {v.x, v.y, v.z}; }
static dvec3 Sub(dvec3 a, dvec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
static dvec3 Scale(double s, dvec3 a) { return {s * a.x, s * a.y, s * a.z}; }
static double DotD(dvec3 a, dvec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static dvec3 AbsD(dvec3 a) { return {std::fabs(a.x), std::fabs(a.y), std::fabs(a.z)}; }
// The sizes of the two products in each component of a x b: what its rounding error scales with.
static dvec3 CrossTerms(dvec3 a, dvec3 b) {
    return {std::fabs(a.y * b.z) + std::fabs(a.z * b.y),
            std::fabs(a.z * b.x) + std::fabs(a.x * b.z),
            std::fabs(a.x * b.y) + std::fabs(a.y * b.x)};
}

// kU, GammaD,
// kPlainRelativeError, kFirstOrderShare and PlaneHitRecord are in robust.h: fast/'s packets
// compute tier 1 too (fast/plane_lanes.h).

// ---- double-double arithmetic (tier 2) ------------------------------------------------------

// A number carried as the unevaluated sum hi + lo, |lo| <= u |hi|: about twice the digits of
// double (Dekker, "A floating-point technique for extending the available precision", Numer.
// Math. 18, 1971). Each operation below is within a few u^2 of the sizes of its operands.
struct DoubleDouble {
    double hi, lo;
};

// a + b exactly (Knuth, TAOCP vol. 2, §4.2.2, TwoSum): the rounded sum and what rounding lost.
static DoubleDouble TwoSum(double a, double b) {
    double s = a + b, bb = s - a;
    return {s, (a - (s - bb)) + (b - bb)};
}
// a * b exactly: the fused multiply-add gives the product's rounding error exactly.
static DoubleDouble TwoProduct(double a, double b) {
    double p = a * b;
    return {p, std::fma(a, b, -p)};
}
// hi + lo put back in the form |lo| <= u |hi| (Dekker's FastTwoSum).
static DoubleDouble Renormalize(double hi, double lo) {
    double s = hi + lo;
    return {s, lo - (s - hi)};
}
static DoubleDouble Add(DoubleDouble x, DoubleDouble y) {
    DoubleDouble s = TwoSum(x.hi, y.hi);
    return Renormalize(s.hi, s.lo + (x.lo + y.lo));
}
static DoubleDouble Mul(DoubleDouble x, DoubleDouble y) {
    DoubleDouble p = TwoProduct(x.hi, y.hi);
    return Renormalize(p.hi, p.lo + (x.hi * y.lo + x.lo * y.hi));
}
static DoubleDouble Neg(DoubleDouble x) { return {-x.hi, -x.lo}; }

struct DoubleDouble3 {
    DoubleDouble x, y, z;
};
// a - b exactly, per component, then times 2^k (exact unless the low part is subnormal). Most
// triangles need no scaling (k = 0), and ldexp is a library call: it is skipped for them.
static DoubleDouble3 ExactDifference(dvec3 a, dvec3 b, int k) {
    DoubleDouble x = TwoSum(a.x, -b.x), y = TwoSum(a.y, -b.y), z = TwoSum(a.z, -b.z);
    if (k == 0)
        return {x, y, z};
    auto scaled = [k](DoubleDouble w) {
        return DoubleDouble{std::ldexp(w.hi, k), std::ldexp(w.lo, k)};
    };
    return {scaled(x), scaled(y), scaled(z)};
}
static DoubleDouble DoubleDoubleDot(DoubleDouble3 a, DoubleDouble3 b) {
    return Add(Add(Mul(a.x, b.x), Mul(a.y, b.y)), Mul(a.z, b.z));
}
static DoubleDouble3 DoubleDoubleCross(DoubleDouble3 a, DoubleDouble3 b) {
    return {Add(Mul(a.y, b.z), Neg(Mul(a.z, b.y))), Add(Mul(a.z, b.x), Neg(Mul(a.x, b.z))),
            Add(Mul(a.x, b.y), Neg(Mul(a.y, b.x)))};
}

// ---- the two tiers ------------------------------------------------------------------------

// The triangle and the ray in double: corner a (tier 2 widens b and c itself), the triangle's
// set-up (its rounded normal, from edges times 2^scale: SetUpTriangle), the ray.
struct PlaneProblem {
    const Triangle *tri;
    const TriangleSetUp *fixed;
    dvec3 a, origin, dir;
};

// The error bound shared by both tiers, first order in the rounding errors: the numerator
// n.(a - o) within eN, the denominator n.d within eD, each normal component within eNormal of
// the exact one. A normal tilted by dn moves the plane at the hit point h by dn.(a - h), which
// is why the way from the hit to the corner enters. Doubled, to cover the second-order terms
// (products of two errors) that the first-order sum leaves out.
static double PlaneError(double t, double denominator, double eN, double eD, dvec3 eNormal,
                         dvec3 toCorner) {
    return 2 * ((eN + std::fabs(t) * eD + DotD(eNormal, AbsD(toCorner))) / std::fabs(denominator));
}

// Tier 1's bound for its t (FindPlaneT below). Rounding bounds (Higham 2002, §3.1): a - o, its
// product with n and the two additions, gamma(4) of sum |n_i (a_i - o_i)|; n.d, gamma(3) of
// sum |n_i d_i|; each normal component, two edge roundings, the products and the subtraction:
// gamma(5) of its two products' sizes; the division, gamma(1) of t.
static inline double PlainError(const PlaneProblem *p, dvec3 toA, double t, double denominator) {
    dvec3 absN = AbsD(p->fixed->n);
    double eN = GammaD(4) * DotD(absN, AbsD(toA));
    double eD = GammaD(3) * DotD(absN, AbsD(p->dir));
    dvec3 toCorner = {toA.x - t * p->dir.x, toA.y - t * p->dir.y, toA.z - t * p->dir.z};
    return PlaneError(t, denominator, eN, eD, p->fixed->nError, toCorner) +
           GammaD(1) * std::fabs(t);
}

// Tier 2: the formula in double-double, from the exact edges and the exact a - o. Every
// operation is within 8 u^2 of its operands' sizes, and no value passes through more than four
// of them, so 32 u^2 of the first-order terms' sizes bounds what they contribute; rounding the
// two sums to double and dividing adds 3 u of t to first order, which gamma(4) covers with room
// for the products of those three roundings.
static PlaneT DoubleDoublePlaneT(const PlaneProblem *p) {
    int k = p->fixed->scale;
    dvec3 b = Widen(p->tri->b), c = Widen(p->tri->c);
    DoubleDouble3 e1 = ExactDifference(b, p->a, k), e2 = ExactDifference(c, p->a, k);
    DoubleDouble3 n = DoubleDoubleCross(e1, e2), toA = ExactDifference(p->a, p->origin, 0);
    DoubleDouble3 d = {{p->dir.x, 0}, {p->dir.y, 0}, {p->dir.z, 0}};
    DoubleDouble numerator = DoubleDoubleDot(n, toA), denominator = DoubleDoubleDot(n, d);
    double t = numerator.hi / denominator.hi;
    dvec3 nHi = {n.x.hi, n.y.hi, n.z.hi}, toAHi = {toA.x.hi, toA.y.hi, toA.z.hi};
    dvec3 e1Hi = {e1.x.hi, e1.y.hi, e1.z.hi}, e2Hi = {e2.x.hi, e2.y.hi, e2.z.hi};
    double u2 = 32 * kU * kU;
    double eN = u2 * DotD(AbsD(nHi), AbsD(toAHi));
    double eD = u2 * DotD(AbsD(nHi), AbsD(p->dir));
    dvec3 eNormal = Scale(u2, CrossTerms(e1Hi, e2Hi));
    double error = PlaneError(t, denominator.hi, eN, eD, eNormal, Sub(toAHi, Scale(t, p->dir)));
    return {t, error + GammaD(4) * std::fabs(t)};
}

// The edges and normal of tier 1, and the box. The edges are scaled by a power of two when they
// lie outside 2^+-64, so that the longer one's largest component is in [1, 2): n is then at
// most 8 (less for a sliver), and n.(a - o) over- or underflows only where a - o itself nearly
// does. Inside 2^+-64 no scaling is needed: n stays within about 2^+-130 of 1 (a sliver aside),
// so n.(a - o) overflows only where a - o is within that factor of overflowing itself, and the
// scene's own numbers would fail first. ldexp scales by any power, in exact steps.
// An edge beyond the range of numbers makes a triangle unhittable whichever corner is written
// first: all three edges are checked, c - b too, which n leaves out. (In double, as the set-up
// works: the difference of two floats is always finite there.)
bool EdgesFinite(const Triangle *tri) {
    dvec3 a = Widen(tri->a), b = Widen(tri->b), c = Widen(tri->c);
    for (dvec3 e : {Sub(b, a), Sub(c, a), Sub(c, b)})
        if (!std::isfinite(e.x) || !std::isfinite(e.y) || !std::isfinite(e.z))
            return false;
    return true;
}

void SetUpTriangle(const Triangle *tri, TriangleSetUp *setUp) {
    setUp->box = TriangleBox(tri);
    dvec3 a = Widen(tri->a), e1 = Sub(Widen(tri->b), a), e2 = Sub(Widen(tri->c), a);
    dvec3 m1 = AbsD(e1), m2 = AbsD(e2);
    double m = std::max({m1.x, m1.y, m1.z, m2.x, m2.y, m2.z});
    setUp->scale = 0; // no scaling
    if (!(m >= 0x1p-64 && m <= 0x1p64) && m > 0 && std::isfinite(m)) {
        int k = setUp->scale = -std::ilogb(m);
        e1 = {std::ldexp(e1.x, k), std::ldexp(e1.y, k), std::ldexp(e1.z, k)};
        e2 = {std::ldexp(e2.x, k), std::ldexp(e2.y, k), std::ldexp(e2.z, k)};
    }
    double yz = e1.y * e2.z, zy = e1.z * e2.y, zx = e1.z * e2.x, xz = e1.x * e2.z;
    double xy = e1.x * e2.y, yx = e1.y * e2.x;
    dvec3 n = setUp->n = {yz - zy, zx - xz, xy - yx}; // CrossD(e1, e2), keeping its products
    // Each component of n: two edge roundings, the products and the subtraction, gamma(5) of
    // its two products' sizes (Higham 2002, §3.1)
    dvec3 nTerms = {std::fabs(yz) + std::fabs(zy), std::fabs(zx) + std::fabs(xz),
                    std::fabs(xy) + std::fabs(yx)};
    dvec3 e = setUp->nError = Scale(GammaD(5), nTerms);
    double largest = std::max({std::fabs(n.x), std::fabs(n.y), std::fabs(n.z)});
    dvec3 size = AbsD(n); // (in double: n as float may overflow or vanish)
    setUp->flat = size.x > size.y ? (size.x > size.z ? 0 : 2) : (size.y > size.z ? 1 : 2);
    setUp->normalKnown = std::max({e.x, e.y, e.z}) <= kFirstOrderShare * largest;
    // How plainly a ray must go away from the triangle to pass over it (PassesOver, robust.h):
    // the unit normal leans from the exact one by at most 2 |n - n*| / |n| <= 2 sum nError_i /
    // max |n_i|, taken twice over, and 16 u covers the rounding of n.d and of the unit normal.
    setUp->awayShare =
        setUp->normalKnown ? (real)(4 * ((e.x + e.y + e.z) / largest)) + 16 * kUnitRoundoff : 0;

    // The unit normal, for shading. A sliver's n may be so small that n.n underflows: then it is
    // scaled by a power of two first, which changes no bit of n / |n|. (Within 2^+-500, n.n, at
    // most three squares of the largest component, stays inside double's normal range, 2^+-1022.)
    setUp->hasArea = largest > 0 && std::isfinite(largest) && EdgesFinite(tri);
    if (setUp->hasArea && !(largest >= 0x1p-500 && largest <= 0x1p500))
        n = Scale(std::ldexp(1.0, -std::ilogb(largest)), n);
    double inverse = 1 / std::sqrt(DotD(n, n));
    setUp->normal = {(real)(inverse * n.x), (real)(inverse * n.y), (real)(inverse * n.z)};
}

// Where the triangle's hit must lie: the window [near, far] in which the ray's line passes its
// box (SlabInterval). Computed only when a t is not plainly inside it (WellInside).
struct Window {
    const Box *box;
    const Ray *ray;
    bool known;
    real near, far;
};

// True if the point o + t d lies within half the window's widening of the triangle's box: then t
// is inside the window, whose other half covers the rounding of this test and of SlabInterval
// (a few u of the same sizes, against 64 u), so moving t into the window would not change it.
// Almost every hit is decided here, with no division.
static inline bool WellInside(const PlaneProblem *p, double t, const Window *w) {
    const Box *box = w->box;
    double pad = 0.5 * ((double)kBoxAllowance * box->size + OriginPad(w->ray));
    const double q[3] = {p->origin.x + t * p->dir.x, p->origin.y + t * p->dir.y,
                         p->origin.z + t * p->dir.z};
    for (int i = 0; i < 3; i++)
        if (!(q[i] >= box->lo[i] - pad && q[i] <= box->hi[i] + pad))
            return false;
    return true;
}

// t moved into the window, its error bound growing by the move; false if the line does not pass
// the box at all. A ray within rounding of an edge, nearly parallel to the triangle, can be
// judged inside while its line meets the plane far beyond the triangle: the hit is then put
// where the line passes the triangle, not out there. That keeps every hit inside its triangle's
// window, which is what lets the BVH skip boxes a ray passes outside. A hit on the triangle is
// inside already (the window is wider than the hit's own error bound), and never moves.
static bool MoveIntoWindow(Window *w, PlaneT *plane) {
    if (!w->known) {
        SlabRay slab = MakeSlabRay(w->ray);
        SlabInterval(w->box->lo, w->box->hi, w->box->size, &slab, &w->near, &w->far);
        w->known = true;
    }
    double t = plane->t < w->near ? w->near : plane->t > w->far ? w->far : plane->t;
    *plane = {t, plane->error + std::fabs(t - plane->t)};
    return w->near <= w->far;
}
static inline bool IntoWindow(const PlaneProblem *p, Window *w, PlaneT *plane) {
    return (!w->known && WellInside(p, plane->t, w)) || MoveIntoWindow(w, plane);
}

// Whether tier 1's bound can be believed: being first order, it leaves out products of two
// errors, which is sound only while each error is small against what it is an error of. With
// the normal known to 2^-10 of its length, and n.d to 2^-10 of its value (counting both the
// rounding of the dot product and the normal's own error, which a ray grazing the plane feels
// in full), what is left out is at most about 2^-9 of what is kept, which PlaneError's factor
// of 2 covers many times over. A triangle whose corners are nearly in a line, or a ray that all
// but skims its plane, fails this: its plain t can be off by far more than the bound says.
// The normal's half depends on the triangle alone: SetUpTriangle decides it (normalKnown).
static inline bool FirstOrderHolds(const PlaneProblem *p, double denominator) {
    dvec3 absD = AbsD(p->dir);
    double eD = GammaD(3) * DotD(AbsD(p->fixed->n), absD) + DotD(p->fixed->nError, absD);
    return p->fixed->normalKnown && eD <= kFirstOrderShare * std::fabs(denominator);
}

// t where the ray meets the triangle's plane, in (tMin, tMax), with its bound: tier 1, then tier 2
// where tier 1's bound cannot decide (the file's opening comment). False if there is none.
// The plane's t counts for a ray whose line passes inside the triangle when it is in
// (tMin, tMax), and above its own error bound, so a ray that starts on this plane, having just
// left it, does not hit it again. Tier 1's t decides alone only where its bound puts it clearly
// outside (tMin, tMax), or clearly inside and within kPlainRelativeError of itself: a long
// triangle's plain t can be off by far more than rounding, enough to put a floor behind a shape
// just beyond it. Everything else, and every triangle whose bound is not sound (FirstOrderHolds),
// goes to tier 2. Both tiers' t are kept in the triangle's window (IntoWindow); moving t there
// changes it by at most as much as it changes t's bound, so tier 1's early answers stay right.
// (QuickPlaneT below repeats tier 1, operation for operation, for the hits it settles alone: a
// change here is a change there.)
static bool FindPlaneT(const PlaneProblem *p, Window *w, real tMin, real tMax, PlaneT *plane) {
    dvec3 toA = Sub(p->a, p->origin);
    double denominator = DotD(p->fixed->n, p->dir);
    double t = DotD(p->fixed->n, toA) / denominator;
    if (!std::isfinite(t)) // the ray is parallel to the plane, or n is 0
        return false;
    *plane = {t, PlainError(p, toA, t, denominator)};
    if (!IntoWindow(p, w, plane))
        return false;
    // Too far to count, whichever tier decides: tier 2's t lies within tier 1's bound of the
    // exact t, so within twice the bound of tier 1's (its own bound being the smaller where it
    // is taken). Behind the origin one bound is enough: tier 2's t is then within its own bound
    // of 0, which the last test below refuses. Only where the bound holds: a triangle's answer
    // must never depend on tMax, or the list and the BVH, which test it against different tMax,
    // would differ.
    bool trusted = FirstOrderHolds(p, denominator);
    bool beyond = !(plane->t - 2 * plane->error < (double)tMax);
    bool behind = !(plane->t + plane->error > 0) || !(plane->t + 2 * plane->error > (double)tMin);
    if (trusted && (beyond || behind))
        return false;
    if (!trusted || !(plane->t - plane->error > 0) ||
        plane->error > kPlainRelativeError * std::fabs(plane->t)) {
        *plane = DoubleDoublePlaneT(p);
        if (!IntoWindow(p, w, plane))
            return false;
    }
    return (real)plane->t > tMin && (real)plane->t < tMax && plane->t > plane->error;
}

// FindPlaneT's answer where tier 1 settles it alone, as almost every hit is: t plainly inside
// the window, the bound trusted, and t either clearly out of (tMin, tMax) or within
// kPlainRelativeError of itself. The same operations as FindPlaneT's, in the same order, so the
// same t, bound and answer; anything else is PLANE_UNSURE, and FindPlaneT starts again.
static inline QuickAnswer QuickPlaneT(const PlaneProblem *p, const Ray *ray, real tMin, real tMax,
                                      PlaneT *plane) {
    dvec3 toA = Sub(p->a, p->origin);
    double denominator = DotD(p->fixed->n, p->dir);
    double t = DotD(p->fixed->n, toA) / denominator;
    if (!std::isfinite(t)) // the ray is parallel to the plane, or n is 0
        return PLANE_MISS;
    double error = PlainError(p, toA, t, denominator);
    Window window = {&p->fixed->box, ray, false, 0, 0};
    if (!WellInside(p, t, &window) || !FirstOrderHolds(p, denominator))
        return PLANE_UNSURE;
    return DecidePlaneT(t, error, tMin, tMax, plane);
}

// Everything QuickPlaneT leaves open: FindPlaneT, from the start. (It makes its own
// PlaneProblem: taking the caller's by address would keep that one in memory on the common path.)
bool SlowPlaneT(const Triangle *tri, const TriangleSetUp *setUp, const Ray *ray, real tMin,
                       real tMax, PlaneT *plane) {
    PlaneProblem p = {tri, setUp, Widen(tri->a), Widen(ray->origin), Widen(ray->dir)};
    Window window = {&setUp->box, ray, false, 0, 0};
    return FindPlaneT(&p, &window, tMin, tMax, plane);
}

// A triangle without a set-up (a caller outside the committed scene): one made for it.
static bool HitWithoutSetUp(const Triangle *tri, const Ray *ray, real tMin, real tMax,
                            RayHit *hit) {
    TriangleSetUp own;
    SetUpTriangle(tri, &own);
    return RobustPlaneHit(tri, &own, ray, tMin, tMax, hit);
}

// The hit record for a triangle whose interior the ray passes through (the caller has decided
// that): t from the plane (FindPlaneT). The point is o + t d, which lies on the plane to within
// its bound: the rounding of o + t d itself, and t's error times |d|.
bool RobustPlaneHit(const Triangle *tri, const TriangleSetUp *setUp, const Ray *ray, real tMin,
                    real tMax, RayHit *hit) {
    if (!setUp)
        return HitWithoutSetUp(tri, ray, tMin, tMax, hit);
    if (!setUp->hasArea)
        return false; // no area: no plane, no normal
    PlaneProblem p = {tri, setUp, Widen(tri->a), Widen(ray->origin), Widen(ray->dir)};
    PlaneT plane;
    QuickAnswer quick = QuickPlaneT(&p, ray, tMin, tMax, &plane);
    if (quick == PLANE_MISS ||
        (quick == PLANE_UNSURE && !SlowPlaneT(tri, setUp, ray, tMin, tMax, &plane)))
        return false;

    return PlaneHitRecord(tri, setUp, ray, plane, hit);
}
