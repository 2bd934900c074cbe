// fast/kernel_packet.h -- the fast shape loop turned the other way for the rays from the eye:
// kLanes rays in the lanes, one shape at a time, where kernel_blocks.h and kernel_spheres.h put
// kLanes shapes in the lanes for one ray. Included by kernel.cpp alone, for its AVX2 copy.
//
// Why: a pixel's samples start at the same eye and go in nearly the same direction, so they meet
// the same shapes. Tested one ray at a time, each sample pays for the blocks' half-empty lanes
// (the assignment's 5 triangles fill 8 lanes) and for setting up each search; tested together,
// every lane is a ray that needs the answer. The answer for each ray is still the plain loop's,
// bit for bit: every line of the first steps below is the scalar line with `Lanes` for `real`
// and the shape's number in every lane (the same operations in the same order, unfused), and
// the shapes that pass go, ray by ray and in scene order, to the very reference functions the
// one-ray kernel calls, with the same interval. So the rays see the shapes in the order the plain
// loop gives them, and every tie is broken as it breaks them. A packet is a pixel's eye rays:
// each searches t in (0, infinity) and leaves no surface.
#pragma once
#include "kernel_spheres.h"
#include "plane_lanes.h"

#include <utility>

// The packet's rays, lane by lane: what Survivors and MayMeet splat for one ray, here one ray a
// lane. Lanes past the packet's end repeat its first ray, and their answers are not kept.
struct PacketLanes {
    Lanes ox, oy, oz; // the sheared test: the origin, axes renamed
    Lanes sx, sy;     // the shear
    Lanes px, py, pz; // the sphere test: the origin, axes as they are
    Lanes dx, dy, dz; // the direction
    Lanes a;          // A = d.d, rounded as Dot rounds it
};

// Each ray's search so far, as TestBlocks and TestLiveSpheres keep it for one ray.
struct PacketSearch {
    const RayPacket *packet;
    unsigned active;    // the packet's rays, a bit each
    real tMax[kLanes];  // each ray's nearest hit so far (infinity: none)
    int best[kLanes];   // each ray's nearest triangle so far; -1: none (or only a sphere)
    bool found[kLanes]; // whether each ray has hit anything
    RayHit *hits;       // each ray's nearest hit
    PlaneRays plane[kLanes / kPlaneLanes]; // the rays again, four at a time, for tier 1's lanes
};

// Ray r has hit a shape.
static RT_INLINE void Found(PacketSearch *p, int r) { p->found[r] = true; }

// One number of each ray of the packet (`value` of the ray in each lane: ray `lane`, or the first
// past `count`) as a vector, made in registers: a vector of scalars stored to memory and at once
// read back as one waits for the stores.
template <typename Value, size_t... lane>
static RT_INLINE Lanes LanesOf(const RayPacket *q, Value value, std::index_sequence<lane...>) {
    return Lanes{value(&q->rays[(int)lane < q->count ? lane : 0])...};
}
template <typename Value> static RT_INLINE Lanes LanesOf(const RayPacket *q, Value value) {
    return LanesOf(q, value, std::make_index_sequence<kLanes>());
}

// Everything a packet's search starts from: the lanes (the rays coordinate by coordinate, each
// lane past `count` repeating the first ray); each ray's search not yet begun, and the rays four
// at a time for tier 1's lanes (plane_lanes.h); and the shear, in lanes, as ShearRay computes it
// for each ray (watertight.cpp): the axes renamed so that kz, the largest component of every
// ray's direction, is z, and sx = d[kx] / d[kz], sy = d[ky] / d[kz].
template <int kz> static RT_INLINE void StartPacket(PacketSearch *p, PacketLanes *l) {
    const RayPacket *q = p->packet;
    l->px = LanesOf(q, [](const Ray *ray) { return ray->origin.x; });
    l->py = LanesOf(q, [](const Ray *ray) { return ray->origin.y; });
    l->pz = LanesOf(q, [](const Ray *ray) { return ray->origin.z; });
    l->dx = LanesOf(q, [](const Ray *ray) { return ray->dir.x; });
    l->dy = LanesOf(q, [](const Ray *ray) { return ray->dir.y; });
    l->dz = LanesOf(q, [](const Ray *ray) { return ray->dir.z; });
    l->a = LanesOf(q, [](const Ray *ray) { return Dot(ray->dir, ray->dir); });
    for (int lane = 0; lane < kLanes; lane++) {
        const Ray *ray = &q->rays[lane < q->count ? lane : 0];
        p->tMax[lane] = kInfinity, p->best[lane] = -1, p->found[lane] = false;
        PlaneRays *w = &p->plane[lane / kPlaneLanes];
        int k = lane % kPlaneLanes;
        w->ox[k] = ray->origin.x, w->oy[k] = ray->origin.y, w->oz[k] = ray->origin.z;
        w->dx[k] = ray->dir.x, w->dy[k] = ray->dir.y, w->dz[k] = ray->dir.z;
        w->tMin[k] = 0, w->originPad[k] = OriginPad(ray);
    }
    const Lanes *o[3] = {&l->px, &l->py, &l->pz}, *d[3] = {&l->dx, &l->dy, &l->dz};
    l->ox = *o[(kz + 1) % 3], l->oy = *o[(kz + 2) % 3], l->oz = *o[kz];
    l->sx = *d[(kz + 1) % 3] / *d[kz], l->sy = *d[(kz + 2) % 3] / *d[kz];
}

// Ray r's RayShear, for the reference test (IntersectWatertight): the numbers of its lane.
static RT_INLINE RayShear LaneShear(const PacketLanes *l, int kz, int r) {
    return {kz, {l->ox[r], l->oy[r], l->oz[r]}, l->sx[r], l->sy[r]};
}

// LineMissesSphere (geometry.cpp) for sphere (c, r2) and every ray of the packet: the bits of the
// rays whose line may meet it. MayMeet's lines, with the rays in the lanes.
static RT_INLINE unsigned RaysMayMeet(vec3 c, real r2, const PacketLanes *l) {
    Lanes centre[3], r2s;
    Fill(&centre[0], c.x), Fill(&centre[1], c.y), Fill(&centre[2], c.z), Fill(&r2s, r2);
    const Lanes o[3] = {l->px, l->py, l->pz}, d[3] = {l->dx, l->dy, l->dz};
    return ~MissingLanes(o, centre, d, &l->a, &r2s);
}

// The spheres: the first step for all the rays at once, sphere by sphere (only sphere blocks'
// lanes that hold one), then for each ray the spheres it may meet, as one ray's search takes them
// (TestLiveSpheres: the plain loop's answer, the nearest first). Each hit lowers its ray's tMax.
// (A packet is made only for a scene of at most kPacketShapes shapes, so a ray's list fits.)
static RT_INLINE void PacketSpheres(const Scene *scene, const SceneLayout *layout,
                                    const PacketLanes *l, PacketSearch *p) {
    const std::vector<SphereBlock> &blocks = layout->sphereBlocks;
    int places[kLanes][kChunkBlocks * kLanes], count[kLanes] = {};
    for (size_t k = 0; k < blocks.size() && k < (size_t)kChunkBlocks; k++) {
        const SphereBlock *b = &blocks[k];
        for (unsigned left = b->filled; left != 0; left &= left - 1) {
            int lane = LowestBit(left);
            vec3 c = {b->center[0][lane], b->center[1][lane], b->center[2][lane]};
            for (unsigned live = RaysMayMeet(c, b->r2[lane], l) & p->active; live != 0;
                 live &= live - 1) {
                int r = LowestBit(live);
                places[r][count[r]++] = (int)k * kLanes + lane;
            }
        }
    }
    for (int r = 0; r < p->packet->count; r++) {
        if (count[r] == 0)
            continue;
        SphereSearch s = StartSphereSearch(scene, -1, &p->packet->rays[r], 0, p->tMax[r], false);
        if (TestLiveSpheres<false>(&s, places[r], count[r], &p->hits[r]))
            p->tMax[r] = s.tMax, Found(p, r);
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

// Ray r's answer for triangle `index`, found by RobustPlaneHit or IntersectWatertight or from the
// lanes: its nearest hit now, if `found`.
static RT_INLINE void Take(PacketSearch *p, int r, int index, bool found) {
    if (!found)
        return;
    p->hits[r].index = p->best[r] = index;
    p->tMax[r] = p->hits[r].t;
    Found(p, r);
}

// The rays of `rays` (bits) whose edge functions for this triangle have certain signs, each to be
// tested against `limit[r]`: RobustPlaneHit for each, with tier 1 in lanes for those that share
// a vector with another (the rest is the scalar function's: PlaneHitRecord for a hit it settles,
// RobustPlaneHit from the start for a ray it leaves unsure).
static RT_INLINE void PlaneHits(const Scene *scene, const SceneLayout *layout, int index,
                                unsigned rays, const real *limit, PacketSearch *p) {
    const Triangle *tri = &scene->triangles[index];
    const TriangleSetUp *setUp = &layout->setUps[index];
    const RayPacket *q = p->packet;
    if (!setUp->hasArea) // no plane: RobustPlaneHit finds nothing
        return;
    for (int chunk = 0; chunk < kLanes / kPlaneLanes; chunk++) {
        unsigned mine = rays >> (chunk * kPlaneLanes) & ((1u << kPlaneLanes) - 1);
        if ((mine & (mine - 1)) == 0) { // one ray or none: the scalar function
            for (; mine != 0; mine &= mine - 1) {
                int r = chunk * kPlaneLanes + LowestBit(mine);
                Take(p, r, index,
                     RobustPlaneHit(tri, setUp, &q->rays[r], 0, limit[r], &p->hits[r]));
            }
            continue;
        }
        PlaneLanes tMax = Same(kInfinity); // (in a register, lane by lane)
        for (unsigned left = mine; left != 0; left &= left - 1) {
            int k = LowestBit(left);
            tMax[k] = limit[chunk * kPlaneLanes + k];
        }
        QuickAnswer answer[kPlaneLanes];
        PlaneT plane[kPlaneLanes];
        QuickPlaneLanes(tri, setUp, &p->plane[chunk], &tMax, kPlaneLanes, answer, plane);
        for (; mine != 0; mine &= mine - 1) {
            int k = LowestBit(mine), r = chunk * kPlaneLanes + k;
            const Ray *ray = &q->rays[r];
            if (answer[k] == PLANE_HIT)
                Take(p, r, index, PlaneHitRecord(tri, setUp, ray, plane[k], &p->hits[r]));
            else if (answer[k] == PLANE_UNSURE)
                Take(p, r, index, RobustPlaneHit(tri, setUp, ray, 0, limit[r], &p->hits[r]));
        }
    }
}

// The triangles, block by block and lane by lane (scene order in a list layout), after the
// spheres: TestBlocks' survivor step for each ray that survives (OutOfReach is not tried here).
template <int kz>
static RT_INLINE void PacketTriangles(const Scene *scene, const SceneLayout *layout,
                                      const PacketLanes *l, PacketSearch *p) {
    const RayPacket *q = p->packet;
    const std::vector<TriangleBlock> &blocks = layout->blocks;
    for (size_t k = 0; k < blocks.size(); k++) {
        const TriangleBlock *b = &blocks[k];
        for (int lane = 0; lane < kLanes; lane++) {
            int index = b->index[lane];
            if (index < 0)
                continue;
            unsigned sure = 0, planeRays = 0;
            unsigned live = RaysSurvive<kz>(b, lane, l, p->active, &sure);
            real limit[kLanes];
            for (; live != 0; live &= live - 1) {
                int r = LowestBit(live);
                limit[r] = p->best[r] >= 0 && index < p->best[r] ? NextAfter(p->tMax[r], true)
                                                                 : p->tMax[r];
                if (sure >> r & 1u) {
                    planeRays |= 1u << r;
                    continue;
                }
                RayShear shear = LaneShear(l, kz, r);
                Take(p, r, index,
                     IntersectWatertight(&scene->triangles[index], &layout->setUps[index],
                                         &q->rays[r], &shear, 0, limit[r], &p->hits[r]));
            }
            if (planeRays != 0)
                PlaneHits(scene, layout, index, planeRays, limit, p);
        }
    }
}

// The whole search for a packet whose rays share the shear's axis kz (RayPacket::kz).
template <int kz>
static RT_INLINE void SearchPacket(const Scene *scene, const SceneLayout *layout, PacketSearch *p) {
    PacketLanes l;
    StartPacket<kz>(p, &l);
    PacketSpheres(scene, layout, &l, p);
    PacketTriangles<kz>(scene, layout, &l, p);
}
