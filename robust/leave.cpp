// robust/leave.cpp -- where a ray that leaves a triangle starts: off the surface, and in from its
// edges, so that it starts inside every closed mesh the triangle belongs to; and on a smooth mesh,
// where the curved surface would be (TerminatorOrigin, at the end).
//
// OffsetRayOrigin moves the hit point off the triangle's plane by the point's error bound, to the
// side the new ray goes. That keeps the ray from meeting the triangle again, but it says nothing
// about the triangles beside it, which meet this one at an edge, at an angle:
// - a hit within rounding of an edge may lie a hair beyond the plane of the neighbour, outside
//   the mesh, and a ray that starts there can leave it;
// - a ray that starts a hair inside the neighbour's plane and grazes toward it meets it next to
//   the shared edge, where the inside test (watertight.cpp) decides which of the two it meets
//   only as finely as its corners round at their distance from the ray's origin: it may give the
//   crossing to the triangle just left, behind the origin, and the ray passes through.
// So the ray starts at least that resolution off the plane (the second), and a point within
// kEdgeMargin resolutions of an edge is first moved in, along the triangle, to that margin (the
// first). Seen across an edge where a neighbour meets the triangle at an angle theta (inside the
// mesh), a point m in from the edge and h off the plane lies inside both when h / m < tan(theta).
#include "robust.h"

#include <algorithm>

// The margin from every edge, in units of the point's error plus the resolution (e): the point
// rounds within sqrt(3) e of where it is meant to be, and the offset lifts it by at most
// sqrt(3) e, so m - sqrt(3) e > sqrt(3) e / tan(theta) keeps every edge whose angle has
// tan(theta) > sqrt(3) / (kEdgeMargin - sqrt(3)): 16 degrees or more (an edge of 90 degrees or
// more at any margin that exceeds the rounding).
const double kEdgeMargin = 8;

// How coarsely the inside test decides at an edge of the triangle whose longest edge has length
// `longest`, for a ray that starts near it: its sheared corners round at their distance from the
// ray's origin, at most that length, in a few roundings (watertight.cpp).
static real Resolution(double longest) { return Gamma(8) * (real)longest; }

static double Max3(double a, double b, double c) {
    return a > b ? (a > c ? a : c) : (b > c ? b : c);
}

// The common case, in straight-line code: whether the hit point p lies more than kEdgeMargin
// resolutions in from every edge of tri. From corner a: the edges e0 = c - b, e1 = b - a,
// e2 = c - a, and q = p - a; w_i, twice the area that p and the edge opposite corner i span,
// projected across the axis k the normal most nearly faces (the second handout's 2D cross
// products), sum to twice the triangle's projected area n_k, and p lies w_i / (n_k |e_i|)
// times |n| (= |n_k| / |unit normal_k|) in from edge i: compared squared, without a root.
// False where the numbers could leave the range of double (beyond 2^-120 to 2^120), and
// NearAnEdge decides; *resolution is set where it returns true.
static bool FarFromEdges(const Triangle *tri, const RayHit *hit, real *resolution) {
    double ax = tri->a.x, ay = tri->a.y, az = tri->a.z;
    double e1x = tri->b.x - ax, e1y = tri->b.y - ay, e1z = tri->b.z - az;
    double e2x = tri->c.x - ax, e2y = tri->c.y - ay, e2z = tri->c.z - az;
    double e0x = e2x - e1x, e0y = e2y - e1y, e0z = e2z - e1z;
    double qx = hit->point.x - ax, qy = hit->point.y - ay, qz = hit->point.z - az;
    double l0 = e0x * e0x + e0y * e0y + e0z * e0z, l1 = e1x * e1x + e1y * e1y + e1z * e1z;
    double l2 = e2x * e2x + e2y * e2y + e2z * e2z, l = Max3(l0, l1, l2);
    if (!(l > 0x1p-240 && l < 0x1p240 && qx * qx + qy * qy + qz * qz < 0x1p240))
        return false;
    vec3 n = Abs(hit->normal);
    double nk, w1, w2; // w1 for corner b (edge c - a), w2 for corner c (edge b - a)
    if (n.x > n.y && n.x > n.z)
        nk = e1y * e2z - e1z * e2y, w1 = qy * e2z - qz * e2y, w2 = e1y * qz - e1z * qy;
    else if (n.y > n.z)
        nk = e1z * e2x - e1x * e2z, w1 = qz * e2x - qx * e2z, w2 = e1z * qx - e1x * qz;
    else
        nk = e1x * e2y - e1y * e2x, w1 = qx * e2y - qy * e2x, w2 = e1x * qy - e1y * qx;
    double w0 = nk - w1 - w2, nMax = Max3(n.x, n.y, n.z);
    *resolution = Resolution(std::sqrt(l));
    double margin = kEdgeMargin * (MaxComponent(hit->pointError) + *resolution);
    double m2 = margin * margin * nMax * nMax;
    return nk * w0 > 0 && nk * w1 > 0 && nk * w2 > 0 && w0 * w0 >= m2 * l0 && w1 * w1 >= m2 * l2 &&
           w2 * w2 >= m2 * l1;
}

// The same numbers, in double, for a point FarFromEdges could not place: every length times
// `unit`, a power of two that keeps their products within the range of numbers.
struct EdgeView {
    dvec3 e[3], q; // e[i]: the edge opposite corner i (c - b, c - a, b - a); q = p - a
    double w[3], nk, length, unit;
};
static double Dot3(dvec3 u, dvec3 v) { return u.x * v.x + u.y * v.y + u.z * v.z; }
static dvec3 Scaled(dvec3 v, double s) { return {v.x * s, v.y * s, v.z * s}; }
static bool SeeEdges(const Triangle *tri, vec3 p, EdgeView *v) {
    dvec3 a = {tri->a.x, tri->a.y, tri->a.z}, b = {tri->b.x, tri->b.y, tri->b.z};
    dvec3 c = {tri->c.x, tri->c.y, tri->c.z};
    v->e[0] = {c.x - b.x, c.y - b.y, c.z - b.z}, v->e[1] = {c.x - a.x, c.y - a.y, c.z - a.z};
    v->e[2] = {b.x - a.x, b.y - a.y, b.z - a.z}, v->q = {p.x - a.x, p.y - a.y, p.z - a.z};
    double largest = 0;
    for (dvec3 u : {v->e[0], v->e[1], v->e[2], v->q})
        largest = Max3(largest, Max3(std::fabs(u.x), std::fabs(u.y), std::fabs(u.z)), 0);
    if (!(largest > 0) || !std::isfinite(largest))
        return false;
    v->unit = std::ldexp(1.0, -std::ilogb(largest)); // exact
    for (dvec3 &u : v->e)
        u = Scaled(u, v->unit);
    v->q = Scaled(v->q, v->unit);
    dvec3 e1 = v->e[2], e2 = v->e[1], q = v->q;
    dvec3 n = {e1.y * e2.z - e1.z * e2.y, e1.z * e2.x - e1.x * e2.z, e1.x * e2.y - e1.y * e2.x};
    double nx = std::fabs(n.x), ny = std::fabs(n.y), nz = std::fabs(n.z);
    int k = nx > ny ? (nx > nz ? 0 : 2) : (ny > nz ? 1 : 2);
    auto cross2 = [k](dvec3 s, dvec3 t) {
        return k == 0   ? s.y * t.z - s.z * t.y
               : k == 1 ? s.z * t.x - s.x * t.z
                        : s.x * t.y - s.y * t.x;
    };
    v->nk = k == 0 ? n.x : k == 1 ? n.y : n.z;
    v->w[1] = cross2(q, e2), v->w[2] = cross2(e1, q), v->w[0] = v->nk - v->w[1] - v->w[2];
    v->length = std::sqrt(Dot3(n, n));
    return v->nk != 0 && std::isfinite(v->length);
}

// The step from p to the point of the triangle at least `margin` (in the view's units) in from
// every edge nearest to p in barycentric measure: each coordinate at least mu_i = margin |e_i| /
// |n|, the excess over them shared out in p's proportions (or evenly, where p has none). In
// double from the view's edges, so that only its final addition to p rounds in `real` (a point
// made from the corners would round at their distance from the origin). False for a point
// already that far in, and for a sliver narrower than two margins, which has no such point.
static bool StepInside(const EdgeView *v, double margin, dvec3 *step) {
    double mu[3], excess[3], total = 0, shortfall = 0;
    for (int i = 0; i < 3; i++) {
        mu[i] = margin * std::sqrt(Dot3(v->e[i], v->e[i])) / v->length;
        total += excess[i] = std::max(0.0, v->w[i] / v->nk - mu[i]);
        shortfall += std::max(0.0, mu[i] - v->w[i] / v->nk);
    }
    double room = 1 - (mu[0] + mu[1] + mu[2]);
    if (!(shortfall > 0) || !(room > 0))
        return false;
    double l1 = mu[1] + (total > 0 ? room * excess[1] / total : room / 3); // of b
    double l2 = mu[2] + (total > 0 ? room * excess[2] / total : room / 3); // of c
    dvec3 e1 = v->e[2], e2 = v->e[1];
    *step = Scaled({l1 * e1.x + l2 * e2.x - v->q.x, l1 * e1.y + l2 * e2.y - v->q.y,
                    l1 * e1.z + l2 * e2.z - v->q.z},
                   1 / v->unit);
    return true;
}

// A point FarFromEdges could not place: moved in to the margin where it lies nearer an edge.
static vec3 NearAnEdge(const Triangle *tri, const RayHit *hit, vec3 dir) {
    EdgeView view;
    if (!SeeEdges(tri, hit->point, &view)) // no area, or beyond the range of numbers
        return OffsetRayOrigin(hit, dir);
    double longest = 0;
    for (const dvec3 &e : view.e)
        longest = std::max(longest, std::sqrt(Dot3(e, e)) / view.unit);
    real resolution = Resolution(longest);
    vec3 least = {resolution, resolution, resolution};
    double margin = kEdgeMargin * (MaxComponent(hit->pointError) + resolution) * view.unit;
    dvec3 step;
    if (!StepInside(&view, margin, &step))
        return OffsetRayOrigin(hit->point, hit->pointError + least, hit->normal, dir);
    vec3 moved = hit->point + vec3{(real)step.x, (real)step.y, (real)step.z};
    // Its error: the step's own rounding in double (a few roundings of the edges' size), its
    // conversion and its addition in `real`
    vec3 error = Gamma(2) * (Abs(moved) + Abs(moved - hit->point)) +
                 real(8 * GammaD(8) * longest) * vec3{1, 1, 1};
    return OffsetRayOrigin(moved, error + least, hit->normal, dir);
}

// The barycentric weights of p, w_i = w[i] / nk from the view's areas (in double, scaled: no
// product over- or underflows), each kept in [0, 1], as a hit point lies on its triangle only to
// within rounding; a triangle the view cannot see gives each corner a third.
static void Weights(const Triangle *tri, vec3 p, real w[3]) {
    EdgeView v;
    if (!SeeEdges(tri, p, &v)) {
        w[0] = w[1] = w[2] = real(1) / 3;
        return;
    }
    double w1 = std::clamp(v.w[1] / v.nk, 0.0, 1.0), w2 = std::clamp(v.w[2] / v.nk, 0.0, 1.0);
    if (w1 + w2 > 1) // (past the far edge by a rounding: back onto it)
        w1 = w1 / (w1 + w2), w2 = 1 - w1;
    w[0] = (real)(1 - w1 - w2), w[1] = (real)w1, w[2] = (real)w2;
}

// The shadow terminator of a smooth mesh: its flat triangles lie inside the curved surface they
// stand for, so a ray toward a light just above the smooth horizon, leaving the flat triangle, is
// stopped by the next triangle over, and the lit side ends in dark, blocky facets. Hanika,
// "Hacking the shadow terminator" (Ray Tracing Gems II, ch. 4, 2021) moves the ray's origin out
// to where the curved surface would be: for each corner i, the point's height below the plane
// through that corner square to its normal n_i, max(0, (p_i - P).n_i), taken along n_i and
// weighted by the point's barycentric weight. A flat region (all normals alike) or a concave one
// (the point above those planes) is not moved. The normals are taken on the side `toward` points
// to. Returns the move; 0 on a flat triangle.
static vec3 TerminatorShift(const Scene *scene, const RayHit *hit, vec3 toward) {
    const Triangle *t = &scene->triangles[hit->index];
    const CornerNormals *c = &scene->cornerNormals[hit->index];
    vec3 outward = hit->frontFace ? hit->normal : -hit->normal;
    real side = Dot(toward, outward) > 0 ? 1 : -1;
    real w[3];
    Weights(t, hit->point, w);
    const vec3 corner[3] = {t->a, t->b, t->c}, normal[3] = {c->a, c->b, c->c};
    vec3 shift = {0, 0, 0};
    for (int i = 0; i < 3; i++) {
        vec3 n = side * normal[i];
        real height = Dot(corner[i] - hit->point, n);
        if (height > 0)
            shift = shift + (w[i] * height) * n;
    }
    return shift;
}

vec3 LeavingPoint(const Scene *scene, const RayHit *hit, vec3 dir) {
    if (hit->shape != SHAPE_TRIANGLE) // a sphere has no edges
        return OffsetRayOrigin(hit, dir);
    const Triangle *tri = &scene->triangles[hit->index];
    real resolution;
    if (!FarFromEdges(tri, hit, &resolution))
        return NearAnEdge(tri, hit, dir);
    vec3 least = {resolution, resolution, resolution};
    return OffsetRayOrigin(hit->point, hit->pointError + least, hit->normal, dir);
}

bool TerminatorOrigin(const Scene *scene, const RayHit *hit, vec3 toward, vec3 *origin) {
    if (!HasCornerNormals(scene, hit))
        return false;
    vec3 shift = TerminatorShift(scene, hit, toward);
    // The move must rise off the face to toward's side by more than its dot product's own
    // rounding: corner normals that lean behind the face, or nearly along it, would otherwise
    // start the ray behind the face it leaves
    vec3 face = Dot(toward, hit->normal) < 0 ? -hit->normal : hit->normal;
    if (!(Dot(shift, face) > Gamma(3) * Dot(Abs(shift), Abs(face))))
        return false;
    // The moved point's error: the hit point's, the sum's own rounding, and the shift's (a few
    // roundings of its size)
    vec3 moved = hit->point + shift;
    vec3 error = hit->pointError + Gamma(1) * Abs(moved) + Gamma(8) * Abs(shift);
    *origin = OffsetRayOrigin(moved, error, hit->normal, toward);
    return true;
}
