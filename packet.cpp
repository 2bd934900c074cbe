// packet.cpp -- a pixel's samples traced together: speed machinery behind TraceRay's contract.
//
// The samples of a pixel leave the same eye in nearly the same direction, meet the same surfaces
// and send their shadow rays to the same lights. TraceEyeRays searches for their nearest hits as
// one packet (FindNearestHitsFromEye), casts the shadow rays their surfaces will ask for, light by
// light, as one packet each (AnyHitsFrom; only where the eye rays made a packet), and only then
// shades each sample in turn as TraceRay would, handing it those answers (KnownShadows). Every
// answer is the one the ray gets alone, so the colours, the ray counts and their sum are
// TraceRay's, bit for bit.
#include "ray.h"

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
