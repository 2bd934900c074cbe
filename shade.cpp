// shade.cpp -- what colour a ray brings back: lighting and the chain of rays.
//
// The assignment handout's diffuse shading with an ambient floor, hard shadows and mirrors; the
// second handout's Phong lighting; the journal's refraction by Snell's law with Fresnel
// weighting. At most `depth` rays in a chain (then black), the background on a miss. Every ray
// asks the scene one of two questions of geometry.cpp: FindNearestHitFrom or AnyHitFrom (a pixel's
// eye rays: FindEyeRayHits, the first question for all of them at once). Last,
// what a render decides once, so that it casts no ray it cannot use: the effects a scene calls
// for, and the shapes that emit (path tracing's lamps).
#include "ray.h"
#include "render.h"

#include <algorithm>

// Adds one shape (or 0: none) to the hash of the shapes a pixel sample's rays met, in order
// (SplitMix64's finaliser, as the jitter's hash).
static uint64_t MixSurface(uint64_t hash, uint64_t shape) { return MixWord(hash, shape); }

// Adds a node for `ray` to the ray tree being recorded; returns its index.
int RecordRay(RayKind kind, const Ray *ray, TraceLog *log) {
    RayNode node = {kind, *ray, false, {}, {0, 0, 0}, log->current};
    log->tree->push_back(node);
    return (int)log->tree->size() - 1;
}

void CloseRay(TraceLog *log, int node, bool found, const RayHit *hit, color light) {
    if (node < 0)
        return;
    RayNode *n = &(*log->tree)[node];
    n->found = found;
    if (found)
        n->record = *hit;
    n->light = light;
}

// What every shading function needs besides the surface: the world, how it is rendered, and
// where the rays cast are counted (and recorded, for a ray tree).
struct ShadeContext {
    const Scene *scene;
    const RenderSettings *settings;
    TraceLog *log;
};

// The surface being shaded: the ray that found it, the hit, its material, and where that ray
// stands in its chain.
struct Surface {
    const Ray *ray;
    const RayHit *hit;
    const Material *m;
    RayChain chain;
};

// A shadow ray as a node of the ray tree being recorded (--pixel), with the nearest shape that
// blocks it.
static void RecordShadowRay(const ShadeContext *sh, const RayHit *hit, const Light *light,
                            bool visible) {
    Methods methods = sh->settings->methods;
    Ray shadow;
    SelfHit from;
    if (ShadowRay(sh->scene, methods, hit, light->position, &shadow, &from)) {
        RayNode *n = &(*sh->log->tree)[RecordRay(RAY_SHADOW, &shadow, sh->log)];
        n->found = FindNearestHitFrom(sh->scene, methods, &shadow, &from, 1, &n->record);
        n->light = visible ? light->intensity : color{0, 0, 0};
    }
}

// The bookkeeping of a shadow ray, which changes no colour: it is counted, its answer goes into
// the hash of what a sample's rays met (adaptive sampling compares them), and when a ray tree is
// being recorded it becomes a node.
static void LogShadowRay(const ShadeContext *sh, const RayHit *hit, const Light *light,
                         bool visible) {
    sh->log->stats.shadow++;
    if (sh->settings->sampling == SAMPLES_ADAPTIVE) // only adaptive sampling reads it
        sh->log->surfaces = MixSurface(sh->log->surfaces, !visible);
    if (sh->log->tree)
        RecordShadowRay(sh, hit, light, visible);
}

// Whether the light shines on the hit: the assignment's hard shadow (LightVisible, geometry.cpp),
// one shadow ray. Without shapes that could block (Effects), no ray is needed.
static bool ShadowTest(const ShadeContext *sh, const RayHit *hit, const Light *light) {
    if (!sh->settings->effects.shadows) // (no shape could stand in the way)
        return true;
    bool visible = LightVisible(sh->scene, sh->settings->methods, hit, light->position);
    LogShadowRay(sh, hit, light, visible);
    return visible;
}

// The assignment handout's rule (`shading floor`): kd * max(ambient, S), where S sums I (N.L)
// over the lights in front of the surface that no shape hides. A light behind the surface
// (N.L <= 0) contributes nothing and costs no shadow ray (second handout). N is the surface's
// normal; on a smooth mesh, the one interpolated from its corners (SurfaceNormal), and a light
// behind the flat triangle is then seen or not as its shadow ray finds (LightVisible).
// Checked by TestFloor (tests/test_handout_light.cpp).
static color FloorColor(const ShadeContext *sh, const Surface *s) {
    const RayHit *hit = s->hit;
    real a = sh->scene->ambientLight; // handout: kd * max(ambient, N.L)
    if (!LightsCanShow(sh->scene, s->m, sh->settings->effects.lightSum))
        return a * s->m->diffuse;
    vec3 n = SurfaceNormal(sh->scene, hit);
    color sum = {0, 0, 0};
    for (const Light &light : sh->scene->lights) {
        if (!Shines(&light))
            continue;
        vec3 toLight = light.position - hit->point;
        real nDotL = Dot(n, toLight);
        if (!(nDotL > 0) || !ShadowTest(sh, hit, &light))
            continue;
        sum = sum + (nDotL / SafeLength(toLight)) * light.intensity; // handout: N.normalize(L)
    }
    return s->m->diffuse * color{std::max(a, sum.x), std::max(a, sum.y), std::max(a, sum.z)};
}

// The second handout's Phong lighting (`shading phong`):
//   ka Ia + sum over visible lights with N.L > 0 of  Ii (kd (N.L) + ks max(0, R.V)^n),
// R = -L + 2 (N.L) N the light's mirror direction, V toward the viewer, all unit vectors.
// The N.L > 0 gate keeps a light below the horizon from making a highlight; max(0, R.V) before
// pow keeps a fractional n from meeting a negative base (a NaN). N as in FloorColor.
// Checked by TestPhong (tests/test_handout_light.cpp).
static color PhongColor(const ShadeContext *sh, const Surface *s) {
    const Material *m = s->m;
    color result = sh->scene->ambientLight * m->ambient;
    vec3 n = SurfaceNormal(sh->scene, s->hit), v = -SafeNormalize(s->ray->dir);
    bool specular = sh->settings->effects.specular && m->specular > 0;
    if (!LightsCanShow(sh->scene, m, sh->settings->effects.lightSum))
        return result;
    for (const Light &light : sh->scene->lights) {
        if (!Shines(&light))
            continue;
        vec3 l = SafeNormalize(light.position - s->hit->point);
        real nDotL = Dot(n, l);
        if (!(nDotL > 0) || !ShadowTest(sh, s->hit, &light))
            continue;
        color term = nDotL * m->diffuse;
        if (specular) {
            vec3 r = (2 * nDotL) * n - l;
            real highlight = m->specular * std::pow(std::max(real(0), Dot(r, v)), m->shininess);
            term = term + color{highlight, highlight, highlight};
            sh->log->stats.specularTerms++;
        }
        result = result + light.intensity * term;
    }
    return result;
}

// The assignment handout's mirror direction of d about the unit normal n: r = d - 2 (d.n) n.
// Checked by TestReflect (tests/test_handout_light.cpp).
vec3 Reflect(vec3 d, vec3 n) { return d - (2 * Dot(d, n)) * n; }

// cos(t), the cosine of the refracted angle, for cos(i) and eta = n1 / n2; false under total
// internal reflection. Snell's law gives cos^2(t) = 1 - eta^2 (1 - cos^2(i)); written that way it
// cancels at grazing incidence (cos(i) near 0), where 1 - cos^2(i) rounds to 1: glass of index 1
// then reflects totally below cos(i) = 1e-8 and bends rays above it. The same quantity as
//   cos^2(t) = (1 - eta)(1 + eta) + (eta cos(i))^2
// has no cancellation (1 - eta is exact for eta in [1/2, 2], Sterbenz), so eta = 1 passes every
// ray straight through, however grazing; for eta > 1 the test for total internal reflection is
// eta cos(i) <= sqrt((eta - 1)(eta + 1)), and hypot keeps (eta cos(i))^2 from underflowing.
static bool RefractedCosine(real cosI, real eta, real *cosT) {
    real etaCos = eta * cosI;
    if (eta <= 1) {
        *cosT = std::hypot(std::sqrt((1 - eta) * (1 + eta)), etaCos); // handout: as below
        return true;
    }
    real m = std::sqrt((eta - 1) * (eta + 1));
    if (!(etaCos > m)) // handout: eta sin(i) > 1, with sin(i) = sqrt(1 - cosI^2)
        return false;
    *cosT = std::sqrt((etaCos - m) * (etaCos + m)); // handout: sqrt(1 - eta^2 (1 - cosI^2))
    return true;
}

// Snell's law, n1 sin(i) = n2 sin(t), for unit d arriving against the unit normal n (d.n <= 0)
// and eta = n1 / n2: t = eta d + (eta cos(i) - cos(t)) n (Shirley & Marschner, FCG §13.1). The
// journal writes the same vector in two parts, after Ray Tracing in One Weekend: r_out_perp =
// eta (d + cos(i) n) and r_out_parallel = -sqrt(1 - |r_out_perp|^2) n, whose sum this is, as
// |r_out_perp|^2 = eta^2 sin^2(i) = 1 - cos^2(t).
// Returns false, and leaves *t alone, for total internal reflection (sin(t) >= 1). The cosine is
// clamped to [0, 1] because d.n of unit vectors can round past 1.
// Checked by TestRefraction (tests/test_handout_light.cpp).
bool Refract(vec3 d, vec3 n, real eta, vec3 *t) {
    real cosI = std::min(real(1), std::max(real(0), -Dot(d, n)));
    real cosT;
    if (!RefractedCosine(cosI, eta, &cosT))
        return false;
    *t = eta * d + (eta * cosI - cosT) * n; // journal: r_out_perp + r_out_parallel
    return true;
}

// The exact Fresnel reflectance of a clear dielectric for unpolarised light, the average of the
// s- and p-polarised amplitudes squared (Hecht, Optics §4.6.2; pbrt-v4 §9.3), for the cosine of
// the incident angle and eta = n1 / n2. 1 under total internal reflection. Exact rather than
// Schlick's approximation, because Schlick is only right on the side of the smaller index:
// evaluated inside glass it misses the rise to 1 at the critical angle.
real FresnelReflectance(real cosI, real eta) {
    cosI = std::min(real(1), std::max(real(0), cosI));
    real cosT;
    if (!RefractedCosine(cosI, eta, &cosT))
        return 1;
    if (!(eta * cosI + cosT > 0)) // a ray exactly along a surface of index 1: nothing to divide
        return 0;
    real rs = (eta * cosI - cosT) / (eta * cosI + cosT);
    real rp = (cosI - eta * cosT) / (cosI + eta * cosT);
    return (rs * rs + rp * rp) / 2;
}

// Schlick, "An Inexpensive BRDF Model for Physically-based Rendering", Computer Graphics Forum
// 13(3), 1994: the exact curve replaced by a fifth power between R0 at normal incidence and 1 at
// grazing. Ray Tracing in One Weekend (§11.4) uses it on both sides of the surface, with the
// incident cosine; inside glass it then misses the rise to 1 before the critical angle, which
// the total internal reflection test supplies.
real SchlickReflectance(real cosI, real eta) {
    cosI = std::min(real(1), std::max(real(0), cosI));
    real cosT;
    if (!RefractedCosine(cosI, eta, &cosT))
        return 1;
    real r0 = (1 - eta) / (1 + eta);
    r0 = r0 * r0;
    return r0 + (1 - r0) * std::pow(1 - cosI, real(5));
}

// Whether the ray `next` is past the assignment's limit on a chain of rays: at most `depth` of
// them, the eye's ray the first. FollowRay sends no ray past it: those are black.
// Checked by TestDepth (tests/test_handout_light.cpp).
static bool PastDepth(const ShadeContext *sh, RayChain next) {
    return next.number > sh->settings->depth;
}

// Sends the next ray of the chain from the hit point in direction dir, if it is allowed: its
// number must not pass `depth`, and its colour, counted with `share` (the mirror fraction or
// the Fresnel weight), must be able to change the pixel (kMinRayWeight). Otherwise black.
static color FollowRay(const ShadeContext *sh, const Surface *s, RayKind kind, vec3 dir,
                       real share) {
    RayChain next = {s->chain.number + 1, s->chain.weight * share};
    if (PastDepth(sh, next)) // the assignment: at most `depth` rays in a chain
        return {0, 0, 0};
    if (next.weight < kMinRayWeight)
        return {0, 0, 0};
    Ray ray;
    SelfHit from;
    LeaveSurface(sh->scene, sh->settings->methods, s->hit, dir, &ray, &from);
    return TraceRay(sh->scene, sh->settings, kind, &ray, &from, next, sh->log);
}

// Clear glass: Fresnel's share R of the reflected ray plus 1 - R of the refracted one. Entering
// (the ray arrives on the outward side) eta = 1 / ior, leaving eta = ior; under total internal
// reflection R = 1 and no refracted ray is cast.
static color GlassColor(const ShadeContext *sh, const Surface *s) {
    vec3 d = SafeNormalize(s->ray->dir), n = s->hit->normal;
    real eta = s->hit->frontFace ? 1 / s->m->ior : s->m->ior;
    real reflectance = sh->settings->methods.fresnel == FRESNEL_SCHLICK
                           ? SchlickReflectance(-Dot(d, n), eta)
                           : FresnelReflectance(-Dot(d, n), eta);
    color result = reflectance * FollowRay(sh, s, RAY_REFLECTION, Reflect(d, n), reflectance);
    vec3 refracted;
    if (reflectance < 1 && Refract(d, n, eta, &refracted))
        result = result +
                 (1 - reflectance) * FollowRay(sh, s, RAY_REFRACTION, refracted, 1 - reflectance);
    return result;
}

// The surface's own colour: glass, or lit by the scene's lighting rule.
static color SurfaceColor(const ShadeContext *sh, const Surface *s) {
    if (s->m->ior > 0)
        return GlassColor(sh, s);
    if (sh->scene->shading == SHADING_PHONG)
        return PhongColor(sh, s);
    return FloorColor(sh, s);
}

// The mirror image of `mirror K`: the reflected ray's colour, times the mirror's tint. A fuzzy
// mirror (Ray Tracing in One Weekend's metal) reflects along a direction drawn from its fuzz
// sphere, another for each ray that meets it, so for each sample of the pixel (FuzzyMirror,
// blur.cpp): the pixel's samples average the spread reflection. One that points into the surface
// is absorbed, as the book's metal absorbs it, and brings back black.
static color MirrorColor(const ShadeContext *sh, const Surface *s, real K) {
    vec3 dir = Reflect(s->ray->dir, s->hit->normal);
    if (s->m->fuzz > 0 &&
        !FuzzyMirror(s->m->fuzz, s->ray, s->hit->normal, sh->settings->path.seed, &dir))
        return {0, 0, 0};
    return s->m->tint * FollowRay(sh, s, RAY_REFLECTION, dir, K);
}

// Mixes the surface's colour with the mirror image: (1 - K) own + K reflected for `mirror K`.
// A perfect mirror (K = 1) never shows its own colour, so it casts no shadow rays; a chain that
// has used up `depth` rays ends in black (FollowRay).
static color ShadeHit(const ShadeContext *sh, const Surface *s) {
    real K = s->m->mirror;
    color result = {0, 0, 0};
    if (K < 1)
        result = (1 - K) * SurfaceColor(sh, s);
    if (K > 0)
        result = result + K * MirrorColor(sh, s, K);
    return result;
}

// The bookkeeping of a ray, which changes no colour: it is counted, its answer goes into the hash
// of what a sample's rays met (adaptive sampling compares them), and when a ray tree is being
// recorded (--pixel) it becomes a node, whose index it returns (or -1) for CloseRay.
static int LogRay(const RenderSettings *settings, RayKind kind, const Ray *ray, bool found,
                  const RayHit *hit, TraceLog *log) {
    CountRay(kind, &log->stats);
    log->stats.primaryHits += kind == RAY_PRIMARY && found;
    if (settings->sampling == SAMPLES_ADAPTIVE) // only adaptive sampling reads the hash
        log->surfaces = MixSurface(log->surfaces, found ? 2 * hit->index + hit->shape + 1 : 0);
    return Record(kind, ray, log);
}

color ShadeFound(const Scene *scene, const RenderSettings *settings, RayKind kind, const Ray *ray,
                 RayChain chain, bool found, const RayHit *hit, TraceLog *log) {
    int node = LogRay(settings, kind, ray, found, hit, log);
    color result = found ? color{0, 0, 0} : BackgroundColor(scene, ray->dir);
    if (found) {
        int parent = log->current;
        log->current = node;
        ShadeContext sh = {scene, settings, log};
        Surface surface = {ray, hit, &scene->materials[hit->material], chain};
        result = ShadeHit(&sh, &surface);
        log->current = parent;
    }
    CloseRay(log, node, found, hit, result);
    return result;
}

color TraceRay(const Scene *scene, const RenderSettings *settings, RayKind kind, const Ray *ray,
               const SelfHit *from, RayChain chain, TraceLog *log) {
    RayHit hit;
    bool found = FindNearestHitFrom(scene, settings->methods, ray, from, kInfinity, &hit);
    return ShadeFound(scene, settings, kind, ray, chain, found, &hit, log);
}

// ---- what a scene calls for ----------------------------------------------------------------

// Whether the lights can change how a surface of material m looks, so that a shadow ray toward
// one could change a pixel: some light shines, and the surface shows its own colour (not a
// perfect mirror, not glass) with some light in it. Under `floor`, kd * max(ambient, S) with S
// at most the lights' sum (N.L <= 1 for unit vectors): only a channel with kd > 0 whose ambient
// floor is below that sum; under `phong`, a diffuse or specular colour; under `path`, a diffuse
// colour (the point lights' next-event rays).
bool LightsCanShow(const Scene *scene, const Material *m, color lightSum) {
    if (!(m->mirror < 1) || m->ior > 0)
        return false;
    color kd = m->diffuse;
    real a = scene->ambientLight;
    if (scene->shading == SHADING_FLOOR)
        return (kd.x > 0 && a < lightSum.x) || (kd.y > 0 && a < lightSum.y) ||
               (kd.z > 0 && a < lightSum.z);
    bool shines = lightSum.x > 0 || lightSum.y > 0 || lightSum.z > 0;
    bool specular = scene->shading == SHADING_PHONG && m->specular > 0;
    return shines && (kd.x > 0 || kd.y > 0 || kd.z > 0 || specular);
}

static bool MaterialIsUsed(const Scene *scene, int material) {
    for (const Sphere &s : scene->spheres)
        if (s.material == material)
            return true;
    for (const Triangle &t : scene->triangles)
        if (t.material == material)
            return true;
    return false;
}

// A triangle's (b - a) x (c - a) with both edges first multiplied by 2^*exponent, the power of
// two that brings the larger edge's largest component into [1, 2): unscaled, the product of two
// edges of 1e200 (or 1e-200) would overflow (or underflow); scaled, its direction is exact and
// its length is 2^(2 exponent) times the true one.
static vec3 ScaledEdgeCross(const Triangle *t, int *exponent) {
    vec3 e1 = t->b - t->a, e2 = t->c - t->a;
    *exponent = UnitExponent(MaxComponent(e1) > MaxComponent(e2) ? e1 : e2);
    return Cross(ScaleByPowerOfTwo(e1, *exponent), ScaleByPowerOfTwo(e2, *exponent));
}

real EmitterSqrtArea(const Scene *scene, const Emitter *e) {
    if (e->shape == SHAPE_SPHERE) // area 4 pi r^2
        return std::sqrt(4 * kPi) * scene->spheres[e->index].radius;
    int exponent; // area |e1 x e2| / 2, from the scaled cross product: 2^(-2 exponent) |n| / 2
    vec3 n = ScaledEdgeCross(&scene->triangles[e->index], &exponent);
    return ScaleByPowerOfTwo(std::sqrt(real(0.5) * SafeLength(n)), -exponent);
}

// An emitting shape, with what every light sample reads: its area's square root, (a triangle) its
// unit normal, and its radiance, once per render.
static Emitter MakeEmitter(const Scene *scene, ShapeKind shape, int index) {
    Emitter e = {shape, index, 0, {0, 0, 0}, {0, 0, 0}};
    e.sqrtArea = EmitterSqrtArea(scene, &e);
    if (shape == SHAPE_SPHERE) {
        e.emit = scene->materials[scene->spheres[index].material].emit;
        return e;
    }
    const Triangle *t = &scene->triangles[index];
    int exponent; // (the scale is not needed: only the direction)
    e.normal = SafeNormalize(ScaledEdgeCross(t, &exponent));
    e.emit = scene->materials[t->material].emit;
    return e;
}

void FindEmitters(const Scene *scene, std::vector<Emitter> *emitters) {
    auto emits = [scene](int material) { return Emits(&scene->materials[material]); };
    // (A shape without area, or of an area beyond the range of numbers, can be neither hit nor
    // sampled: it is left out, so no density is ever divided by 0 or infinity.)
    auto add = [scene, emitters](ShapeKind shape, int index) {
        Emitter e = MakeEmitter(scene, shape, index);
        if (e.sqrtArea > 0 && std::isfinite(e.sqrtArea))
            emitters->push_back(e);
    };
    for (int i = 0; i < (int)scene->spheres.size(); i++)
        if (emits(scene->spheres[i].material))
            add(SHAPE_SPHERE, i);
    for (int i = 0; i < (int)scene->triangles.size(); i++)
        if (emits(scene->triangles[i].material))
            add(SHAPE_TRIANGLE, i);
}

void PlanEffects(const Scene *scene, const RenderSettings *settings, Effects *effects) {
    bool shapes = !scene->spheres.empty() || !scene->triangles.empty();
    bool lights = false, path = scene->shading == SHADING_PATH;
    for (const Light &light : scene->lights)
        lights = lights || Shines(&light);
    *effects = Effects{false, false, false, false, settings->samplesPerPixel > 1, false, {}, {}};
    effects->defocus = scene->camera.kind == CAMERA_LOOKAT && scene->camera.lensRadius > 0;
    for (const Light &light : scene->lights)
        effects->lightSum = effects->lightSum + light.intensity;
    bool chain = settings->depth > 1; // room for a ray after the primary one
    for (int k = 0; k < (int)scene->materials.size(); k++) {
        const Material *m = &scene->materials[k];
        if (!MaterialIsUsed(scene, k))
            continue;
        effects->reflection = effects->reflection || (chain && (m->mirror > 0 || m->ior > 0));
        effects->refraction = effects->refraction || (chain && m->ior > 0);
        effects->fuzz = effects->fuzz || (chain && m->mirror > 0 && m->fuzz > 0);
        effects->shadows =
            effects->shadows || (shapes && LightsCanShow(scene, m, effects->lightSum));
        effects->specular =
            effects->specular || (scene->shading == SHADING_PHONG && lights && m->specular > 0);
        bool diffuse = m->mirror < 1 && !(m->ior > 0) && MaxComponent(m->diffuse) > 0;
        effects->indirect = effects->indirect || (path && chain && diffuse);
    }
    if (path)
        FindEmitters(scene, &effects->emitters);
}
