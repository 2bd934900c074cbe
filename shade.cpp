// shade.cpp -- what colour a ray brings back: lighting and the chain of rays, nothing else.
//
// The assignment handout's diffuse shading with an ambient floor, hard shadows from point lights
// and mirror reflection, at most `depth` rays in a chain (then black), the background on a miss.
// Every ray kind asks the scene the same two questions of geometry.cpp: FindNearestHit, AnyHit.
#include "ray.h"

// Whether the segment from the hit point to the light is free of shapes. The shadow ray runs
// from a safe origin (OffsetRayOrigin) with dir = light - origin, so t = 1 is the light itself
// and the open interval (0, 1) holds every possible blocker, however far away the light is.
static bool LightIsVisible(const Scene *scene, const RenderSettings *settings, const RayHit *hit,
                           vec3 lightPosition, RayStats *stats) {
    Ray shadow;
    shadow.origin = OffsetRayOrigin(hit, lightPosition - hit->point);
    shadow.dir = lightPosition - shadow.origin;
    stats->shadow++;
    return !AnyHit(scene, settings->triangleMethod, &shadow, 0, 1);
}

// The handout's lighting rule (`shading floor`): colour = kd * max(ambient, S), where S sums
// I * (N.L) over the lights in front of the surface that no shape hides. A light behind the
// surface (N.L <= 0) contributes nothing and costs no shadow ray (second handout).
static color LocalColor(const Scene *scene, const RenderSettings *settings, const RayHit *hit,
                        const Material *m, RayStats *stats) {
    color sum = {0, 0, 0};
    for (const Light &light : scene->lights) {
        vec3 toLight = light.position - hit->point;
        real nDotL = Dot(hit->normal, toLight);
        if (!(nDotL > 0))
            continue;
        if (!LightIsVisible(scene, settings, hit, light.position, stats))
            continue;
        sum = sum + (nDotL / Length(toLight)) * light.intensity;
    }
    color floor = {scene->ambient, scene->ambient, scene->ambient};
    return m->diffuse * Max(floor, sum);
}

// Mirror reflection of the incoming direction about the normal: r = d - 2 (d.N) N (handout).
// r has the length of d; only its direction matters to the next ray.
static color ReflectedColor(const Scene *scene, const RenderSettings *settings, const Ray *ray,
                            const RayHit *hit, int rayNumber, RayStats *stats) {
    Ray reflected;
    reflected.dir = ray->dir - (2 * Dot(ray->dir, hit->normal)) * hit->normal;
    reflected.origin = OffsetRayOrigin(hit, reflected.dir);
    stats->reflection++;
    return TraceRay(scene, settings, &reflected, rayNumber + 1, stats);
}

// Mixes the local colour with the reflected one: (1 - K) local + K reflected for `mirror K`.
// A perfect mirror (K = 1) does not light its own surface, so it casts no shadow rays; the chain
// stops with black once `depth` rays have been cast.
static color ShadeHit(const Scene *scene, const RenderSettings *settings, const Ray *ray,
                      const RayHit *hit, int rayNumber, RayStats *stats) {
    const Material *m = &scene->materials[hit->material];
    color result = {0, 0, 0};
    if (m->mirror < 1)
        result = (1 - m->mirror) * LocalColor(scene, settings, hit, m, stats);
    if (m->mirror > 0 && rayNumber < settings->depth)
        result = result + m->mirror * ReflectedColor(scene, settings, ray, hit, rayNumber, stats);
    return result;
}

color TraceRay(const Scene *scene, const RenderSettings *settings, const Ray *ray, int rayNumber,
               RayStats *stats) {
    RayHit hit;
    if (!FindNearestHit(scene, settings->triangleMethod, ray, 0, kInfinity, &hit))
        return scene->background;
    return ShadeHit(scene, settings, ray, &hit, rayNumber, stats);
}
