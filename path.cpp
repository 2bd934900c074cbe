// path.cpp -- `shading path`: the learning journal's diffuse scattering, as a path tracer.
//
// A pixel is the Monte Carlo estimate of the light that reaches the eye after any number of
// bounces (Kajiya, "The Rendering Equation", SIGGRAPH 1986). This file holds the journal's
// estimator as Ray Tracing in One Weekend writes it (`--estimator journal`): a diffuse hit sends
// the ray on toward normal + a random unit vector and multiplies what it brings back by the
// reflectance, until a miss or the depth cap. rt's estimator (the default, path_full.cpp) is
// that one with four steps beyond it: next-event estimation, multiple importance sampling,
// cosine sampling drawn directly, and Russian roulette. Emitting surfaces (`emit`) give off their
// radiance on both sides; a ray that escapes brings the background, light from every direction.
// Random numbers come from a hash of (pixel, sample, bounce, dimension), so the image never
// depends on the thread count; they, the scattered directions and the points drawn on emitters
// are in path_sampling.h. Pixels are written sRGB-encoded (render.cpp).
#include "path.h"

// A mirror's or glass's next ray, picked by the number `pick` in [0, 1) in proportion to the
// surface's shares: the mirror fraction K reflects; of the rest, glass reflects Fresnel's share R
// and refracts the others (or reflects, under total internal reflection). Each choice is made
// with the probability of its share, so the shares drop out of the estimate. Writes the ray that
// leaves the surface (`out` may be `in`) and its kind; false where a fuzzy mirror's direction,
// drawn from its fuzz sphere with the numbers a diffuse bounce would scatter with (a bounce that
// reflects does not scatter), points into the surface: the book's metal absorbs it.
bool MirrorOrGlass(const Path *path, const Ray *in, const RayHit *hit, const Material *m, real pick,
                   Ray *out, SelfHit *from, RayKind *kind) {
    const Scene *scene = path->scene;
    Methods methods = path->settings->methods;
    vec3 d = SafeNormalize(in->dir), n = hit->normal, dir = Reflect(d, n);
    *kind = RAY_REFLECTION;
    if (pick < m->mirror) {
        vec2 disk = m->fuzz > 0 ? DiskPoint(&path->sample, path->bounce, SCATTER_DISK) : vec2{};
        if (m->fuzz > 0 && !FuzzReflect(d, n, m->fuzz, RandomUnitVector(disk), &dir))
            return false;
        LeaveSurface(scene, methods, hit, dir, out, from);
        return true;
    }
    real eta = hit->frontFace ? 1 / m->ior : m->ior, cosI = -Dot(d, n);
    real reflectance = methods.fresnel == FRESNEL_SCHLICK ? SchlickReflectance(cosI, eta)
                                                          : FresnelReflectance(cosI, eta);
    vec3 refracted;
    bool reflect = (pick - m->mirror) < reflectance * (1 - m->mirror) || // (the same number,
                   !Refract(d, n, eta, &refracted);                      // past K)
    LeaveSurface(scene, methods, hit, reflect ? dir : refracted, out, from);
    *kind = reflect ? RAY_REFLECTION : RAY_REFRACTION;
    return true;
}

// ---- the journal's estimator -----------------------------------------------------------------

// Ray Tracing in One Weekend's ray_color (§9.1), with its Lambertian, metal and dielectric
// scattering (§9.4, §10, §11) and emitted light (The Next Week, §7), for ray number `number` of
// the path, whose nearest hit has been searched for (`found`, *hit):
//   colour = background                                    on a miss
//          = emitted + attenuation * colour(scattered ray)  at a hit
// and black for a ray past `depth`. A diffuse surface scatters toward normal + a random unit
// vector, which has density cos(theta) / pi, so BRDF cos / density is the reflectance: the
// attenuation. A mirror or glass attenuates by nothing. Light arrives only where a ray happens
// to hit an emitting surface or escapes: a point light, which no ray can hit, lights nothing.
static color JournalColor(Path *path, const Ray *ray, const SelfHit *from, RayKind kind,
                          int number);

static color JournalShade(Path *path, const Ray *ray, bool found, const RayHit *hit, int number) {
    if (!found)
        return BackgroundColor(path->scene, ray->dir);
    const Material *m = &path->scene->materials[hit->material];
    if (number == path->settings->depth) // the next ray would be one too many: black
        return m->emit;
    path->bounce = number - 1;
    real pick = Random(path, PICK_SURFACE);
    Ray next;
    SelfHit leaving;
    if (pick < m->mirror || m->ior > 0) { // (a mirror's reflection is tinted; glass's is not)
        RayKind kind;
        if (!MirrorOrGlass(path, ray, hit, m, pick, &next, &leaving, &kind))
            return m->emit;
        color tint = pick < m->mirror ? m->tint : color{1, 1, 1};
        return m->emit + tint * JournalColor(path, &next, &leaving, kind, number + 1);
    }
    if (!(MaxComponent(m->diffuse) > 0)) // black: what a ray would bring back counts for 0
        return m->emit;
    vec3 n = SurfaceNormal(path->scene, hit); // (on a smooth mesh, interpolated)
    vec3 toward = n + RandomUnitVector(DiskPoint(&path->sample, number - 1, SCATTER_DISK));
    if (!(Dot(toward, n) > 0)) // the random vector all but -normal: no way out
        toward = n;
    if (!(Dot(toward, hit->normal) > 0)) // into the flat triangle it stands for: absorbed
        return m->emit;
    LeaveSurface(path->scene, path->settings->methods, hit, toward, &next, &leaving);
    return m->emit + m->diffuse * JournalColor(path, &next, &leaving, RAY_DIFFUSE, number + 1);
}

// A ray of the journal's path whose nearest hit has been searched for: counted, recorded in the
// ray tree if one is being drawn (its colour is what it brings back), and shaded.
static color JournalRay(Path *path, const Ray *ray, RayKind kind, bool found, const RayHit *hit,
                        int number) {
    TraceLog *log = path->log;
    CountRay(kind, &log->stats);
    int node = Record(kind, ray, log), parent = log->current;
    log->current = node;
    color result = JournalShade(path, ray, found, hit, number);
    log->current = parent;
    CloseRay(log, node, found, hit, result);
    return result;
}

static color JournalColor(Path *path, const Ray *ray, const SelfHit *from, RayKind kind,
                          int number) {
    RayHit hit;
    bool found =
        FindNearestHitFrom(path->scene, path->settings->methods, ray, from, kInfinity, &hit);
    return JournalRay(path, ray, kind, found, &hit, number);
}

color TracePath(const Scene *scene, const RenderSettings *settings, const Ray *primary, bool found,
                const RayHit *hit, int i, int j, int s, TraceLog *log) {
    log->stats.primaryHits += found;
    Path path = {scene,
                 settings,
                 log,
                 PathKey(settings->path.seed, i, j, s),
                 0,
                 {0, 0, 0},
                 {1, 1, 1},
                 *primary,
                 kNoSelfHit,
                 RAY_PRIMARY,
                 0,
                 {0, 0, 0},
                 SHAPE_SPHERE,
                 -1,
                 false,
                 {0, 0, 0},
                 {0, 0, 0}};
    if (settings->path.estimator == ESTIMATOR_JOURNAL)
        return JournalRay(&path, primary, RAY_PRIMARY, found, hit, 1);
    return FullPath(&path, found, hit);
}
