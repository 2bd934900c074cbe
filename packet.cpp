// packet.cpp -- a pixel's samples traced together: speed machinery behind TraceRay's contract.
//
// First the search: whether packets pay in a scene, and the nearest hits of a packet of eye rays
// or the any-hits of a packet of shadow rays, each exactly what the one-ray search
// (FindNearestHitFrom, AnyHitFrom) answers, where the kernel takes them (HitCommittedPacket).
// Then the tracing:
// The samples of a pixel leave the same eye in nearly the same direction, meet the same surfaces
// and send their shadow rays to the same lights. TraceEyeRays searches for their nearest hits as
// one packet (FindNearestHitsFromEye), casts the shadow rays their surfaces will ask for, light by
// light, as one packet each (AnyHitsFrom; only where the eye rays made a packet), and only then
// shades each sample in turn as TraceRay would, handing it those answers (KnownShadows). Every
// answer is the one the ray gets alone, so the colours, the ray counts and their sum are
// TraceRay's, bit for bit.
#include "ray.h"
#include "render.h"
#include "robust.h"

// Whether a packet of `count` rays costs less than its rays one by one. A packet tests each
// shape once for all its rays, where one ray tests a block of kLanes shapes at once, and a
// packet's test of one shape costs a little more than one ray's test of a block; what the packet
// saves is each ray's own set-up and the blocks' empty lanes, which matter in small scenes.
// Measured (callgrind, one thread, 4 to 16 spp), with packets against without: the assignment's
// 8 shapes, the Cornell box's 14 and a 50-triangle list gain (by 11%, 3% and 2%); a 162-triangle
// list loses 8%, the test scene's 139 triangles as a list 5%, a 1,285-triangle list 14%; and a
// packet of one ray is one ray's search with more bookkeeping. Hence two rays or more, and at
// most kPacketShapes shapes.
const size_t kPacketShapes = 64;
static bool PacketPays(const SceneLayout *layout, int count) {
    return count >= 2 && layout->triangleCount + layout->sphereCount <= kPacketShapes;
}

bool PacketsPay(const Scene *scene, Methods methods, int count) {
    return methods.triangle == TRIANGLE_WATERTIGHT && methods.sphere != SPHERE_TEXTBOOK &&
           LayoutIsCurrent(scene) && SpheresAreCurrent(scene) && scene->layout.wide &&
           scene->layout.nodes.empty() && count <= kLanes && PacketPays(&scene->layout, count);
}

// The packet is taken only where it pays (PacketsPay), and where no ray is one that ScaleRay
// would rescale. False where it is not taken.
static bool HitPacket(const Scene *scene, Methods methods, RayPacket *packet, RayHit *hits,
                      bool *found) {
    if (!PacketsPay(scene, methods, packet->count))
        return false;
    packet->kz = DominantAxis(packet->rays[0].dir);
    for (int r = 0; r < packet->count; r++) {
        vec3 d = packet->rays[r].dir;
        if (!SearchedAsIs(d) ||            // else ScaleRay would rescale it
            DominantAxis(d) != packet->kz) // one renaming of the axes for all
            return false;
    }
    return HitCommittedPacket(scene, packet, hits, found);
}

bool FindNearestHitsFromEye(const Scene *scene, Methods methods, const Ray *rays, int count,
                            RayHit *hits, bool *found) {
    RayStart starts[kLanes];
    for (int r = 0; r < count && r < kLanes; r++)
        starts[r] = kFromTheEye;
    RayPacket packet = {rays, starts, count, 2, kInfinity, false};
    if (HitPacket(scene, methods, &packet, hits, found))
        return true;
    for (int r = 0; r < count; r++)
        found[r] = FindNearestHitFrom(scene, methods, &rays[r], &kFromTheEye, kInfinity, &hits[r]);
    return false;
}

void AnyHitsFrom(const Scene *scene, Methods methods, const Ray *rays, const RayStart *starts,
                 int count, real tMax, bool *blocked) {
    RayHit scratch[kLanes];
    RayPacket packet = {rays, starts, count, 2, tMax, true};
    if (HitPacket(scene, methods, &packet, scratch, blocked))
        return;
    for (int r = 0; r < count; r++)
        blocked[r] = AnyHitFrom(scene, methods, &rays[r], &starts[r], tMax);
}

// Whether the surface of this hit will ask for shadow rays: it shows its own colour (it is not a
// perfect mirror, nor glass: ShadeHit, shade.cpp). Which lights it asks about, the lighting rule
// decides; a ray cast here for a light it does not ask about is wasted, never wrong.
static bool ShowsOwnColour(const Scene *scene, const RayHit *hit) {
    const Material *m = &scene->materials[hit->material];
    return m->mirror < 1 && !(m->ior > 0);
}

// The shadow rays of the samples' surfaces toward each light in front of them, one packet a light:
// each ray made by ShadowRay, as LightIsVisible makes it.
static void CastFirstShadows(const Scene *scene, const RenderSettings *settings, const RayHit *hits,
                             const bool *found, int count, KnownShadows *known) {
    const Methods *methods = &settings->methods;
    for (size_t l = 0; l < scene->lights.size() && l < (size_t)kKnownLights; l++) {
        vec3 position = scene->lights[l].position;
        Ray rays[kLanes];
        RayStart starts[kLanes];
        int sample[kLanes], n = 0;
        for (int r = 0; r < count; r++) {
            const RayHit *hit = &hits[r];
            if (!found[r] || !ShowsOwnColour(scene, hit) ||
                !(Dot(hit->normal, position - hit->point) > 0)) // a light behind: never asked
                continue;
            if (ShadowRay(hit, position, methods, &rays[n], &starts[n]))
                sample[n++] = r;
            else
                known[r].answer[l] = SHADOW_NO_RAY;
        }
        bool blocked[kLanes];
        if (n > 0)
            AnyHitsFrom(scene, *methods, rays, starts, n, 1, blocked);
        for (int k = 0; k < n; k++)
            known[sample[k]].answer[l] = blocked[k] ? SHADOW_BLOCKED : SHADOW_VISIBLE;
    }
}

void TraceEyeRays(const Scene *scene, const RenderSettings *settings, const Ray *rays, int count,
                  TraceLog *log, color *sum) {
    RayHit hits[kLanes];
    bool found[kLanes];
    KnownShadows known[kLanes] = {}; // SHADOW_UNKNOWN
    bool packet = FindNearestHitsFromEye(scene, settings->methods, rays, count, hits, found);
    // Where the eye rays could not be a packet, neither can their shadow rays; and a ray tree
    // records each ray as it is cast
    bool cast = packet && settings->effects.shadows && !log->tree;
    if (cast)
        CastFirstShadows(scene, settings, hits, found, count, known);
    for (int k = 0; k < count; k++)
        *sum = *sum + TraceFoundEyeRay(scene, settings, &rays[k], found[k], &hits[k],
                                       cast ? &known[k] : nullptr, log);
}
