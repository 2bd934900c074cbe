// path.cpp -- `shading path`: the learning journal's diffuse scattering, as a path tracer.
//
// A pixel is the Monte Carlo estimate of the light that reaches the eye after any number of
// bounces (Kajiya, "The Rendering Equation", SIGGRAPH 1986). The file opens with the journal's
// estimator as Ray Tracing in One Weekend writes it (`--estimator journal`): a diffuse hit sends
// the ray on toward normal + a random unit vector and multiplies what it brings back by the
// reflectance, until a miss or the depth cap. rt's estimator (the default) is that one with four
// steps beyond it, each marked: next-event estimation (the light arriving straight from the
// lights, at every diffuse hit), multiple importance sampling (MIS), cosine sampling drawn
// directly, and Russian roulette. Emitting surfaces (`emit`) give off their radiance on both
// sides; a point light of intensity I gives irradiance I cos(theta) / r^2; a ray that escapes
// brings the background, light from every direction. Random numbers come from a hash of (pixel,
// sample, bounce, dimension), so the image never depends on the thread count; they, the
// scattered directions and the points drawn on emitters are in path_sampling.h. Pixels are
// written sRGB-encoded (render.cpp).
#include "path_sampling.h"
#include "render.h"
#include "robust/robust.h" // robust/: StartLeaving, for rays from Depart's point

// The decisions of one bounce, each with a hash of its own (PathHash), and the hashes of its two
// disk points: the scattered direction's and a point on an emitting sphere's (DiskPoint).
enum Decision {
    PICK_SURFACE,
    PICK_EMITTER,
    EMITTER_UV, // a pair (PathRandomPair)
    ROULETTE,
    SCATTER_DISK,
    EMITTER_DISK = SCATTER_DISK + kDiskDimensions,
    DECISIONS = EMITTER_DISK + kDiskDimensions
};
static_assert(DECISIONS <= kDimensionsPerBounce, "each bounce's numbers must be its own");

// A path being followed: its random numbers, the light gathered so far, the share of light the
// next vertex passes on to the pixel, the ray to follow, and what the last bounce was.
struct Path {
    const Scene *scene;
    const RenderSettings *settings;
    TraceLog *log;
    PathSample sample;
    int bounce;    // 0 for the primary ray's vertex
    color light;   // gathered so far (rt's estimator)
    color through; // the throughput: what the next vertex's light counts in the pixel
    Ray ray;       // the ray to follow
    SelfHit from;  // and what it must not hit (the surface it leaves)
    RayKind kind;
    real scatterPdf;  // the density the last diffuse bounce drew the ray with; 0: not diffuse
    vec3 scatteredAt; // and the point it was drawn at, on the shape (kind, index) below
    ShapeKind scatteredShape;
    int scatteredIndex;
    bool departs; // the rays from this diffuse hit start at `departure` (Depart)
    vec3 departure;
    vec3 shading; // the diffuse hit's SurfaceNormal: its lighting and scattering use it (a
                  // scattered ray must also leave on the side of its geometric normal)
};

// RecordRay for a path's rays, with no call where no tree is being drawn (every pixel but the
// one `--pixel` names).
static int Record(RayKind kind, const Ray *ray, TraceLog *log) {
    return log->tree ? RecordRay(kind, ray, log) : -1;
}

static real Random(const Path *path, Decision d) {
    return PathRandom(&path->sample, path->bounce, d);
}

// A mirror's or glass's next ray, picked by the number `pick` in [0, 1) in proportion to the
// surface's shares: the mirror fraction K reflects; of the rest, glass reflects Fresnel's share R
// and refracts the others (or reflects, under total internal reflection). Each choice is made
// with the probability of its share, so the shares drop out of the estimate. Writes the ray that
// leaves the surface (`out` may be `in`) and its kind; false where a fuzzy mirror's direction,
// drawn from its fuzz sphere with the numbers a diffuse bounce would scatter with (a bounce that
// reflects does not scatter), points into the surface: the book's metal absorbs it.
static bool MirrorOrGlass(const Path *path, const Ray *in, const RayHit *hit, const Material *m,
                          real pick, Ray *out, SelfHit *from, RayKind *kind) {
    const Scene *scene = path->scene;
    const Methods *methods = &path->settings->methods;
    vec3 d = SafeNormalize(in->dir), n = hit->normal, dir = Reflect(d, n);
    *kind = RAY_REFLECTION;
    if (pick < m->mirror) {
        vec2 disk = m->fuzz > 0 ? DiskPoint(&path->sample, path->bounce, SCATTER_DISK) : vec2{};
        if (m->fuzz > 0 && !FuzzReflect(d, n, m->fuzz, RandomUnitVector(disk), &dir))
            return false;
        LeaveSurface(scene, hit, dir, methods, out, from);
        return true;
    }
    real eta = hit->frontFace ? 1 / m->ior : m->ior, cosI = -Dot(d, n);
    real reflectance = methods->fresnel == FRESNEL_SCHLICK ? SchlickReflectance(cosI, eta)
                                                           : FresnelReflectance(cosI, eta);
    vec3 refracted;
    bool reflect = (pick - m->mirror) < reflectance * (1 - m->mirror) || // (the same number,
                   !Refract(d, n, eta, &refracted);                      // past K)
    LeaveSurface(scene, hit, reflect ? dir : refracted, methods, out, from);
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
    LeaveSurface(path->scene, hit, toward, &path->settings->methods, &next, &leaving);
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

// ---- rt's estimator: the journal's, and four steps beyond it --------------------------------

// Step 1, next-event estimation: at every diffuse hit, the light that reaches it straight from the
// point lights and the emitting shapes, each through a shadow ray, added to the path's light.
// Rays leave the surface as LeaveSurface says; under the bound all of them to the side the normal
// faces, so one offset point serves them all (Depart).

// Where the rays from a diffuse hit start. All go to the side its normal faces (each is cast
// only with cos theta > 0), and the self-hit bound moves the hit point off the surface to that
// side whatever the direction (DeparturePoint): one point, moved once a vertex. Under the other
// methods LeaveSurface and ShadowRay decide for each ray.
static void Depart(Path *path, const RayHit *hit) {
    path->departs = path->settings->methods.selfHit == SELF_HIT_BOUND;
    if (path->departs)
        path->departure =
            DeparturePoint(path->scene, &path->settings->methods, hit, hit->normal, hit->normal);
}

// ShadowRay from the hit to `target`, from the departure point when there is one.
static bool CastShadow(const Path *path, const RayHit *hit, vec3 target, Ray *ray, SelfHit *from) {
    if (!path->departs)
        return ShadowRay(path->scene, hit, target, &path->settings->methods, ray, from);
    *ray = {path->departure, target - path->departure};
    *from = StartLeaving(path->scene, hit, hit->normal, ray->dir);
    return ray->dir.x != 0 || ray->dir.y != 0 || ray->dir.z != 0;
}

// Whether point p (unit normal n) of emitter e can face the shaded hit at all: from outside a
// sphere only its near half can be seen, the points whose normal leans toward the hit; from
// inside, all of it. A triangle is seen from both sides.
static bool Faces(const Scene *scene, const Emitter *e, const RayHit *hit, vec3 p, vec3 n) {
    if (e->shape != SHAPE_SPHERE)
        return true;
    const Sphere *s = &scene->spheres[e->index];
    bool inside = hit->shape == SHAPE_SPHERE && hit->index == e->index
                      ? !hit->frontFace // on the sphere itself: the side it was hit from
                      : SafeLength(hit->point - s->center) < s->radius;
    return inside || Dot(n, hit->point - p) > 0;
}

// How far short of p (t = 1) EmitterVisible stops looking. The ray meets e at t = 1 to within
// the rounding of p's coordinates against its distance, about u |p| / |p - o|: an eighth of this
// or less in double unless e is nearer than some 2^-30 of its coordinates' size, and in float
// unless it is nearer than about half of it. So e itself, and whatever lies beyond it, is out of
// reach (where e is nearer than that and is found all the same, it counts as seen).
const real kShortOfEmitter = real(0x1p-20);

// Whether nothing stands between the shaded hit and the point p of emitter e, which faces it: no
// shape but e is hit on the way to p (the line meets a facing point of a sphere, or a triangle,
// nowhere before p). The search stops 2^-20 of the way short of p, so the shapes it does not look
// at are e, those beyond it (the ceiling behind a lamp, which the box test, OutOfReach, refuses
// before any plane test), and a shape within 2^-20 of the way in front of p, which touches e
// there. (Looking for e itself, to just past p, would take a p that the line misses by a
// rounding, on the very edge of e, as hidden; and under --self-hit skip, which skips the sphere a
// ray leaves, a point on the inside of a glowing sphere would never see the rest of it.)
static bool EmitterVisible(Path *path, const RayHit *hit, const Emitter *e, vec3 p) {
    const Methods *methods = &path->settings->methods;
    Ray shadow;
    SelfHit from;
    if (!CastShadow(path, hit, p, &shadow, &from))
        return false;
    path->log->stats.shadow++;
    int node = Record(RAY_SHADOW, &shadow, path->log);
    RayHit blocker;
    bool found =
        FindNearestHitFrom(path->scene, *methods, &shadow, &from, 1 - kShortOfEmitter, &blocker);
    bool visible = !found || (blocker.shape == e->shape && blocker.index == e->index);
    if (node >= 0) {
        RayNode *n = &(*path->log->tree)[node];
        n->hit = found && !visible;
        if (found)
            n->record = blocker;
    }
    return visible;
}

// Next-event estimation for the point lights: each gives irradiance I cos(theta) / r^2 where no
// shape hides it, and the BRDF rho / pi turns that into light toward the eye. A point light can
// never be hit by a scattered ray, so this is its only way into the image.
static color PointLights(Path *path, const RayHit *hit, color rho) {
    color sum = {0, 0, 0};
    for (const Light &light : path->scene->lights) {
        if (!Shines(&light))
            continue;
        vec3 toLight = light.position - hit->point;
        real distance = SafeLength(toLight);
        real cosTheta = Dot(path->shading, toLight) / distance;
        if (!(cosTheta > 0))
            continue;
        Ray shadow;
        SelfHit from;
        if (CastShadow(path, hit, light.position, &shadow, &from)) {
            path->log->stats.shadow++;
            int node = Record(RAY_SHADOW, &shadow, path->log);
            bool blocked = AnyHitFrom(path->scene, path->settings->methods, &shadow, &from, 1);
            if (node >= 0)
                (*path->log->tree)[node].hit = blocked;
            if (blocked)
                continue;
        }
        sum = sum + (cosTheta / (distance * distance)) * light.intensity;
    }
    return (1 / kPi) * rho * sum;
}

// The cone in which emitting sphere e is seen from point x of shape (kind, index), where next-event
// estimation draws its points in one; false where it draws them over the sphere's area: when
// asked to, and from x on the sphere itself or inside it, where any point of it may face x.
static bool EmitterCone(const Path *path, const Emitter *e, vec3 x, ShapeKind kind, int index,
                        SphereCone *cone) {
    return e->shape == SHAPE_SPHERE && path->settings->path.spheres == SPHERES_CONE &&
           !(kind == SHAPE_SPHERE && index == e->index) &&
           ConeOfSphere(&path->scene->spheres[e->index], x, cone);
}

// Next-event estimation for the emitting shapes: one emitter picked uniformly, one point on it
// (a sphere's in the cone it is seen in, else uniform over the area), its light times the BRDF and
// cos(theta) over the density of picking it, weighted against the scattered ray's chance of
// finding the same point (step 2, MIS).
static color Emitters(Path *path, const RayHit *hit, color rho, bool last) {
    const std::vector<Emitter> &emitters = path->settings->effects.emitters;
    if (emitters.empty() || path->settings->path.lights == LIGHTS_NONE)
        return {0, 0, 0};
    size_t k =
        std::min(emitters.size() - 1, (size_t)(Random(path, PICK_EMITTER) * emitters.size()));
    const Emitter *e = &emitters[k];
    vec3 p, n = e->normal;
    SphereCone cone = {};
    bool inCone = EmitterCone(path, e, hit->point, hit->shape, hit->index, &cone);
    if (inCone)
        p = SampleSphereCone(&path->scene->spheres[e->index], &cone,
                             PathRandomPair(&path->sample, path->bounce, EMITTER_UV), &n);
    else if (e->shape == SHAPE_SPHERE)
        SampleSphere(&path->scene->spheres[e->index],
                     DiskPoint(&path->sample, path->bounce, EMITTER_DISK), &p, &n);
    else
        p = SampleTriangle(&path->scene->triangles[e->index],
                           PathRandomPair(&path->sample, path->bounce, EMITTER_UV));
    vec3 toPoint = p - hit->point;
    real distance = SafeLength(toPoint); // (rescaled where its square would leave the numbers)
    real cosTheta = Dot(path->shading, toPoint) / distance;
    real cosLight = std::fabs(Dot(n, toPoint)) / distance;
    if (!(cosTheta > 0) || !(cosLight > 0) || (!inCone && !Faces(path->scene, e, hit, p, n)) ||
        !EmitterVisible(path, hit, e, p))
        return {0, 0, 0};
    real pdf = inCone ? ConePdf(emitters.size(), &cone)
                      : EmitterPdf(emitters.size(), e->sqrtArea, distance, cosLight);
    real weight = path->settings->path.lights == LIGHTS_MIS && !last // (no scattered ray follows
                      ? PowerHeuristic(pdf, ScatterPdf(path->settings->path.scatter, cosTheta))
                      : 1; // the last vertex to share the light with)
    return (weight * cosTheta / (kPi * pdf)) * (rho * e->emit);
}

// Step 2, multiple importance sampling (Veach 1997): a point of an emitter can be found two ways,
// by next-event estimation and by a scattered ray that hits it; each counts with a weight, and the
// weights of the two ways add up to 1 (PowerHeuristic). The share of an emitter's light that a
// path adds when its ray hits it: all of it after the
// camera or a mirror or glass (no next-event estimation could have found that point), none
// when next-event estimation alone counts emitters, and under MIS the scattered ray's weight.
static real EmissionWeight(const Path *path, const RayHit *hit) {
    LightMethod lights = path->settings->path.lights;
    if (path->scatterPdf == 0 || lights == LIGHTS_NONE)
        return 1;
    if (lights == LIGHTS_NEE)
        return 0;
    Emitter e = {hit->shape, hit->index, 0, {0, 0, 0}, {0, 0, 0}};
    size_t count = path->settings->effects.emitters.size();
    SphereCone cone = {};
    if (EmitterCone(path, &e, path->scatteredAt, path->scatteredShape, path->scatteredIndex, &cone))
        return PowerHeuristic(path->scatterPdf, ConePdf(count, &cone));
    real length = SafeLength(path->ray.dir), distance = hit->t * length;
    real cosLight = std::fabs(Dot(hit->normal, path->ray.dir)) / length;
    real pdf = EmitterPdf(count, EmitterSqrtArea(path->scene, &e), distance, cosLight);
    return PowerHeuristic(path->scatterPdf, pdf);
}

// The next ray of the path from a hit on material m, and what the bounce does to the
// throughput; false if the path ends here. One random number picks what the surface does, in
// proportion to its shares (MirrorOrGlass); a diffuse surface adds the light that reaches it
// from the lights (step 1) and scatters (step 3).
// At the last vertex a chain allows (`last`), no ray follows: a diffuse surface still adds the
// light straight from the lights, as the other shadings' shadow rays do at any depth.
static bool Bounce(Path *path, const RayHit *hit, const Material *m, bool last) {
    real pick = Random(path, PICK_SURFACE);
    path->scatterPdf = 0;
    if (pick < m->mirror || m->ior > 0) {
        if (last ||
            !MirrorOrGlass(path, &path->ray, hit, m, pick, &path->ray, &path->from, &path->kind))
            return false;
        if (pick < m->mirror) // (a mirror's reflection is tinted; glass's is not)
            path->through = path->through * m->tint;
        return true;
    }
    color rho = m->diffuse;
    if (!(MaxComponent(rho) > 0)) // black: it scatters nothing, not even the lights' light
        return false;
    path->shading = SurfaceNormal(path->scene, hit);
    Depart(path, hit); // step 1: the emitters' shadow ray first, then the point lights'
    color direct = Emitters(path, hit, rho, last);
    if (!path->scene->lights.empty())
        direct = PointLights(path, hit, rho) + direct;
    path->light = path->light + path->through * direct;
    if (last)
        return false;
    ScatterMethod method = path->settings->path.scatter; // step 3: cosine sampling, drawn
    vec3 n = path->shading;
    vec3 dir = ScatterDirection(method, n, DiskPoint(&path->sample, path->bounce, SCATTER_DISK));
    real cosTheta = Dot(dir, n);
    if (!(cosTheta > 0) || !(Dot(dir, hit->normal) > 0)) // (below the flat triangle: absorbed)
        return false;
    // The estimator's factor BRDF cos / density: with cosine sampling cos / pi over cos / pi,
    // which cancels exactly, so it is rho itself (the white furnace's exact answer)
    path->scatterPdf = ScatterPdf(method, cosTheta);
    path->scatteredAt = hit->point, path->scatteredShape = hit->shape;
    path->scatteredIndex = hit->index;
    path->through = path->through *
                    (method == SCATTER_COSINE ? rho : (cosTheta / (kPi * path->scatterPdf)) * rho);
    path->kind = RAY_DIFFUSE;
    if (!path->departs) // robust/: the else, from Depart's point
        LeaveSurface(path->scene, hit, dir, &path->settings->methods, &path->ray, &path->from);
    else
        path->ray = {path->departure, dir},
        path->from = StartLeaving(path->scene, hit, hit->normal, dir);
    return true;
}

// Step 4, Russian roulette (Arvo & Kirk, "Particle Transport and Image Synthesis", SIGGRAPH 1990):
// a path whose throughput has fallen to q < 1 goes on with probability q, its throughput divided by
// q, so the expected light is unchanged while dim paths end early. From the third ray on, so the
// first bounces, which carry most of the light, are always followed.
static bool Survives(Path *path) {
    real q = std::min(real(1), MaxComponent(path->through));
    if (q >= 1)
        return true;
    if (!(Random(path, ROULETTE) < q))
        return false;
    path->through = (1 / q) * path->through;
    return true;
}

// What the ray tree shows for a path's rays (`--pixel`): each ray's node, and the light and
// throughput when it was cast, from which the light it brought back follows at the end.
struct PathNode {
    int node;
    color lightBefore, through;
};

static void FinishTree(const Path *path, const std::vector<PathNode> &nodes) {
    for (const PathNode &p : nodes) {
        color after = path->light - p.lightBefore, *out = &(*path->log->tree)[p.node].light;
        *out = {p.through.x > 0 ? after.x / p.through.x : 0,
                p.through.y > 0 ? after.y / p.through.y : 0,
                p.through.z > 0 ? after.z / p.through.z : 0};
    }
}

color TracePath(const Scene *scene, const RenderSettings *settings, const Ray *primary, int i,
                int j, int s, TraceLog *log) {
    RayHit hit;
    bool found =
        FindNearestHitFrom(scene, settings->methods, primary, &kNoSelfHit, kInfinity, &hit);
    return TraceFoundPath(scene, settings, primary, found, &hit, i, j, s, log);
}

// rt's estimator, one vertex a turn: the emitted light of what the ray hit (weighted by MIS),
// then the bounce, until a miss, the depth cap, or roulette.
static color FullPath(Path *path, bool foundFirst, const RayHit *firstHit) {
    const Scene *scene = path->scene;
    const RenderSettings *settings = path->settings;
    TraceLog *log = path->log;
    std::vector<PathNode> nodes;
    int parent = log->current;
    for (int number = 1; number <= settings->depth; number++, path->bounce++) {
        CountRay(path->kind, &log->stats);
        int node = Record(path->kind, &path->ray, log);
        if (node >= 0)
            nodes.push_back({node, path->light, path->through});
        RayHit hit;
        bool found = number == 1 ? foundFirst // the eye ray's, found already
                                 : FindNearestHitFrom(scene, settings->methods, &path->ray,
                                                      &path->from, kInfinity, &hit);
        if (number == 1 && found)
            hit = *firstHit;
        if (node >= 0 && ((*log->tree)[node].hit = found))
            (*log->tree)[node].record = hit;
        if (!found) {
            path->light = path->light + path->through * BackgroundColor(scene, path->ray.dir);
            break;
        }
        const Material *m = &scene->materials[hit.material];
        if (Emits(m))
            path->light = path->light + EmissionWeight(path, &hit) * (path->through * m->emit);
        log->current = node;
        if (!Bounce(path, &hit, m, number == settings->depth) ||
            (!settings->path.noRoulette && number >= 2 && !Survives(path)))
            break;
    }
    log->current = parent;
    if (log->tree)
        FinishTree(path, nodes);
    return path->light;
}

color TraceFoundPath(const Scene *scene, const RenderSettings *settings, const Ray *primary,
                     bool found, const RayHit *hit, int i, int j, int s, TraceLog *log) {
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
