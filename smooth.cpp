// smooth.cpp -- smooth meshes: the shading normal of a triangle whose corners carry normals (a
// mesh file's `vn`), interpolated across it (Phong shading, Phong 1975: "Illumination for
// computer generated pictures"). A mesh of flat triangles that stands for a curved surface is
// lit as the surface, while every intersection, offset and self-hit decision keeps the flat
// triangle's own (geometric) normal, as pbrt-v4 keeps the two apart (§3.10.2). And where a ray
// that leaves a smooth mesh starts: out at the curved surface, where the way there is free.
#include "ray.h"
#include "robust/robust.h" // robust/: LeavingPoint and TerminatorOrigin, for DeparturePoint

#include <algorithm>

// The barycentric weights of point p of triangle t, p = w0 a + w1 b + w2 c: with the edges
// e1 = b - a, e2 = c - a and q = p - a, w1 = (q x e2).n / n.n and w2 = (e1 x q).n / n.n for
// n = e1 x e2 (each is the share of the area that p cuts off opposite that corner). The lengths
// are first brought near 1 by a power of two (exact), so no product over- or underflows at any
// scale. A hit point lies on its triangle only to within rounding, so the weights are kept in
// [0, 1]; a triangle with no area gives each corner a third.
void Barycentric(const Triangle *t, vec3 p, real w[3]) {
    vec3 e1 = t->b - t->a, e2 = t->c - t->a, q = p - t->a;
    int exponent = UnitExponent({MaxComponent(e1), MaxComponent(e2), 0});
    e1 = ScaleByPowerOfTwo(e1, exponent), e2 = ScaleByPowerOfTwo(e2, exponent),
    q = ScaleByPowerOfTwo(q, exponent);
    vec3 n = Cross(e1, e2);
    real nn = Dot(n, n);
    if (!(nn > 0) || !std::isfinite(nn)) {
        w[0] = w[1] = w[2] = real(1) / 3;
        return;
    }
    real w1 = std::clamp(Dot(Cross(q, e2), n) / nn, real(0), real(1));
    real w2 = std::clamp(Dot(Cross(e1, q), n) / nn, real(0), real(1));
    if (w1 + w2 > 1) // (past the far edge by a rounding: back onto it)
        w1 = w1 / (w1 + w2), w2 = 1 - w1;
    w[0] = 1 - w1 - w2, w[1] = w1, w[2] = w2;
}

vec3 SmoothNormal(const Scene *scene, const RayHit *hit) {
    const CornerNormals *c = &scene->cornerNormals[hit->index];
    real w[3];
    Barycentric(&scene->triangles[hit->index], hit->point, w);
    vec3 n = SafeNormalize(w[0] * c->a + w[1] * c->b + w[2] * c->c);
    if (!(MaxComponent(n) > 0)) // (opposite normals that cancel: the flat triangle's)
        return hit->normal;
    // The corner normals lean to the triangle's outward side (the mesh reader sees to it); a
    // ray that arrived on the other side sees the other side of the smooth surface too
    return hit->frontFace ? n : -n;
}

vec3 DeparturePoint(const Scene *scene, Methods methods, const RayHit *hit, vec3 dir, vec3 toward) {
    if (!HasCornerNormals(scene, hit))
        return LeavingPoint(scene, hit, dir);
    // robust: never behind the face it leaves, whatever the ray's direction; a ray toward a light
    // behind the flat triangle then meets it (or the mesh around it) and finds the light hidden
    vec3 flat = LeavingPoint(scene, hit, toward), moved;
    if (!TerminatorOrigin(scene, hit, toward, &moved))
        return flat;
    // robust: the move out to the curved surface passes through nothing, nor does as long a way
    // beyond it (so no shape lies within rounding of where the ray starts): else the ray would
    // start past a wall, a floor or another part of the mesh that the hit itself cannot see
    Ray way = {flat, moved - flat};
    return AnyHit(scene, methods, &way, 0, 2) ? flat : moved;
}
