// kernel_packet.h -- the fast shape loop turned the other way for the rays from the eye: kLanes
// rays in the lanes, one shape at a time, where kernel_blocks.h and kernel_spheres.h put kLanes
// shapes in the lanes for one ray. Included by kernel.cpp alone, for its AVX2 copy.
//
// Why: a pixel's samples start at the same eye and go in nearly the same direction, so they meet
// the same shapes. Tested one ray at a time, each sample pays for the blocks' half-empty lanes
// (the assignment's 5 triangles fill 8 lanes) and for setting up each search; tested together,
// every lane is a ray that needs the answer. The answer for each ray is still the plain loop's,
// bit for bit: every line of the first steps below is the scalar line with `Lanes` for `real`
// and the shape's number in every lane (the same operations in the same order, unfused), and
// the shapes that pass go, ray by ray and in scene order, to the very reference functions the
// one-ray kernel calls, with the same interval. So the rays see the shapes in the order the plain
// loop gives them, and every tie is broken as it breaks them.
#pragma once
#include "kernel_spheres.h"

// The packet's rays, lane by lane: what Survivors and MayMeet splat for one ray, here one ray a
// lane. Lanes past the packet's end repeat its first ray, and their answers are not kept.
struct PacketLanes {
    Lanes ox, oy, oz; // the sheared test: the origin, axes renamed
    Lanes sx, sy;     // the shear
    Lanes px, py, pz; // the sphere test: the origin, axes as they are
    Lanes dx, dy, dz; // the direction
    Lanes a;          // A = d.d, rounded as Dot rounds it
};

// Each ray's search so far, as TestBlocks and HitLiveSpheres keep it for one ray.
struct PacketSearch {
    const RayPacket *packet;
    unsigned active;                 // the rays still searching (an any-hit search drops each hit)
    real tMin[kLanes], tMax[kLanes]; // each ray's interval; tMax: its nearest hit so far
    int skipSphere[kLanes], skipTriangle[kLanes]; // the shape each ray leaves (RayStart); -1: none
    int best[kLanes];   // each ray's nearest triangle so far; -1: none (or only a sphere)
    bool found[kLanes]; // whether each ray has hit anything
    RayHit *hits;       // each ray's nearest hit
};

// Ray r has hit a shape: an any-hit search is over for it.
static RT_INLINE void Found(PacketSearch *p, int r) {
    p->found[r] = true;
    if (p->packet->anyHit)
        p->active &= ~(1u << r);
}

static RT_INLINE void SetLane(Lanes *v, int lane, real x) { (*v)[lane] = x; }

// The lanes, from each ray's RayShear (renamed origin, shear) and its Ray (origin, direction).
static RT_INLINE void FillPacketLanes(const PacketSearch *p, PacketLanes *l) {
    for (int lane = 0; lane < kLanes; lane++) {
        int r = lane < p->packet->count ? lane : 0;
        const RayShear *k = &p->packet->shears[r];
        const Ray *ray = &p->packet->rays[r];
        SetLane(&l->ox, lane, k->origin.x), SetLane(&l->oy, lane, k->origin.y);
        SetLane(&l->oz, lane, k->origin.z), SetLane(&l->sx, lane, k->sx);
        SetLane(&l->sy, lane, k->sy);
        SetLane(&l->px, lane, ray->origin.x), SetLane(&l->py, lane, ray->origin.y);
        SetLane(&l->pz, lane, ray->origin.z), SetLane(&l->dx, lane, ray->dir.x);
        SetLane(&l->dy, lane, ray->dir.y), SetLane(&l->dz, lane, ray->dir.z);
        SetLane(&l->a, lane, Dot(ray->dir, ray->dir));
    }
}

// LineMissesSphere (geometry.cpp) for sphere (c, r2) and every ray of the packet: the bits of the
// rays whose line may meet it. MayMeet's lines, with the rays in the lanes.
static RT_INLINE unsigned RaysMayMeet(vec3 c, real r2, const PacketLanes *l) {
    Lanes cx, cy, cz, r2s, zero, tiny;
    Fill(&cx, c.x), Fill(&cy, c.y), Fill(&cz, c.z), Fill(&r2s, r2), Fill(&zero, 0);
    Fill(&tiny, std::numeric_limits<real>::min());
    Lanes fx = l->px - cx, fy = l->py - cy, fz = l->pz - cz; // f = o - c
    Lanes ux = fy * l->dz - fz * l->dy;                      // f x d, as Cross writes it
    Lanes uy = fz * l->dx - fx * l->dz;
    Lanes uz = fx * l->dy - fy * l->dx;
    Lanes ar2 = l->a * r2s;
    Lanes disc = ar2 - (ux * ux + uy * uy + uz * uz); // Dot: (x x + y y) + z z
    LaneMask misses = (disc < zero) & (ar2 >= tiny);
    return ~LaneBits(&misses);
}

// The spheres, in scene order (HitLiveSpheres for each ray): only sphere blocks' lanes that hold
// one. Each hit lowers its ray's tMax.
static RT_INLINE void PacketSpheres(const Scene *scene, const PacketLanes *l, PacketSearch *p) {
    const std::vector<SphereBlock> &blocks = scene->layout.sphereBlocks;
    for (size_t k = 0; k < blocks.size() && p->active != 0; k++) {
        const SphereBlock *b = &blocks[k];
        for (unsigned left = b->filled; left != 0; left &= left - 1) {
            int lane = __builtin_ctz(left), i = (int)k * kLanes + lane;
            vec3 c = {b->center[0][lane], b->center[1][lane], b->center[2][lane]};
            unsigned live = RaysMayMeet(c, b->r2[lane], l) & p->active;
            for (; live != 0; live &= live - 1) {
                int r = __builtin_ctz(live);
                RayHit *hit = &p->hits[r];
                if (i == p->skipSphere[r] ||
                    !IntersectSphere(&scene->spheres[i], &p->packet->rays[r], p->tMin[r],
                                     p->tMax[r], hit))
                    continue;
                hit->index = i;
                p->tMax[r] = hit->t;
                Found(p, r);
            }
        }
    }
}

// EdgesDisagree (watertight.cpp) for one triangle of block b and the packet's rays (bits `rays`):
// the bits of the rays that survive, and in *sure those whose three edge functions are neither 0
// nor NaN. Survivors' lines, with the rays in the lanes.
template <int kz>
static RT_INLINE unsigned RaysSurvive(const TriangleBlock *b, int lane, const PacketLanes *l,
                                      unsigned rays, unsigned *sure) {
    Lanes s[6], zero;
    Fill(&zero, 0);
    for (int corner = 0; corner < 3; corner++) {
        Lanes Ax, Ay, Az;
        Fill(&Ax, b->corner[3 * corner + (kz + 1) % 3][lane]);
        Fill(&Ay, b->corner[3 * corner + (kz + 2) % 3][lane]);
        Fill(&Az, b->corner[3 * corner + kz][lane]);
        Ax = Ax - l->ox, Ay = Ay - l->oy, Az = Az - l->oz;
        s[2 * corner] = Ax - l->sx * Az;
        s[2 * corner + 1] = Ay - l->sy * Az;
    }
    Lanes u = s[4] * s[3] - s[5] * s[2]; // cx by - cy bx
    Lanes v = s[0] * s[5] - s[1] * s[4]; // ax cy - ay cx
    Lanes w = s[2] * s[1] - s[3] * s[0]; // bx ay - by ax
    LaneMask uNeg = u < zero, vNeg = v < zero, wNeg = w < zero;
    LaneMask uPos = u > zero, vPos = v > zero, wPos = w > zero;
    LaneMask out = (uNeg | vNeg | wNeg) & (uPos | vPos | wPos);
    unsigned live = ~LaneBits(&out) & rays;
    if (live == 0) // most triangles, for most packets
        return 0;
    LaneMask certain = (uNeg | uPos) & (vNeg | vPos) & (wNeg | wPos);
    *sure = LaneBits(&certain);
    return live;
}

// The triangles, block by block and lane by lane (scene order in a list layout), after the
// spheres: TestBlocks' survivor step for each ray that survives, with its own interval.
template <int kz>
static RT_INLINE void PacketTriangles(const Scene *scene, const PacketLanes *l, PacketSearch *p) {
    const RayPacket *q = p->packet;
    const std::vector<TriangleBlock> &blocks = scene->layout.blocks;
    for (size_t k = 0; k < blocks.size() && p->active != 0; k++) {
        const TriangleBlock *b = &blocks[k];
        for (int lane = 0; lane < kLanes; lane++) {
            int index = b->index[lane];
            if (index < 0)
                continue;
            unsigned sure = 0;
            unsigned live = RaysSurvive<kz>(b, lane, l, p->active, &sure);
            for (; live != 0; live &= live - 1) {
                int r = __builtin_ctz(live);
                if (index == p->skipTriangle[r])
                    continue;
                real limit = p->best[r] >= 0 && index < p->best[r] ? NextAfter(p->tMax[r], true)
                                                                   : p->tMax[r];
                const Triangle *tri = &scene->triangles[index];
                const TriangleSetUp *setUp = &scene->layout.setUps[index];
                RayHit *hit = &p->hits[r];
                if (!(sure >> r & 1u
                          ? RobustPlaneHit(tri, setUp, &q->rays[r], p->tMin[r], limit, hit)
                          : IntersectWatertight(tri, setUp, &q->rays[r], &q->shears[r], p->tMin[r],
                                                limit, hit)))
                    continue;
                hit->index = p->best[r] = index;
                p->tMax[r] = hit->t;
                Found(p, r);
            }
        }
    }
}

// The whole search for a packet whose rays share the shear's axis kz.
template <int kz> static RT_INLINE void SearchPacket(const Scene *scene, PacketSearch *p) {
    PacketLanes l;
    FillPacketLanes(p, &l);
    PacketSpheres(scene, &l, p);
    PacketTriangles<kz>(scene, &l, p);
}
