// path_full.cpp -- rt's estimator for `shading path`: the journal's (path.cpp), and four steps
// beyond it, each marked: next-event estimation (the light arriving straight from the lights, at
// every diffuse hit), multiple importance sampling (MIS), cosine sampling drawn directly, and
// Russian roulette. A point light of intensity I gives irradiance I cos(theta) / r^2.
#include "path.h"
#include "robust/robust.h" // robust/: StartLeaving, for rays from Depart's point

#include <algorithm>
#include <vector>

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
            DeparturePoint(path->scene, path->settings->methods, hit, hit->normal, hit->normal);
}

// ShadowRay from the hit to `target`, from the departure point when there is one.
static bool CastShadow(const Path *path, const RayHit *hit, vec3 target, Ray *ray, SelfHit *from) {
    if (!path->departs)
        return ShadowRay(path->scene, path->settings->methods, hit, target, ray, from);
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
    Methods methods = path->settings->methods;
    Ray shadow;
    SelfHit from;
    if (!CastShadow(path, hit, p, &shadow, &from))
        return false;
    path->log->stats.shadow++;
    int node = Record(RAY_SHADOW, &shadow, path->log);
    RayHit blocker;
    bool found =
        FindNearestHitFrom(path->scene, methods, &shadow, &from, 1 - kShortOfEmitter, &blocker);
    bool visible = !found || (blocker.shape == e->shape && blocker.index == e->index);
    if (node >= 0) {
        RayNode *n = &(*path->log->tree)[node];
        n->found = found && !visible;
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
        real cosTheta = Dot(path->shadingNormal, toLight) / distance;
        if (!(cosTheta > 0))
            continue;
        Ray shadow;
        SelfHit from;
        if (CastShadow(path, hit, light.position, &shadow, &from)) {
            path->log->stats.shadow++;
            int node = Record(RAY_SHADOW, &shadow, path->log);
            bool blocked = AnyHitFrom(path->scene, path->settings->methods, &shadow, &from, 1);
            if (node >= 0)
                (*path->log->tree)[node].found = blocked;
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
    real cosTheta = Dot(path->shadingNormal, toPoint) / distance;
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
    path->shadingNormal = SurfaceNormal(path->scene, hit);
    Depart(path, hit); // step 1: the emitters' shadow ray first, then the point lights'
    color direct = Emitters(path, hit, rho, last);
    if (!path->scene->lights.empty())
        direct = PointLights(path, hit, rho) + direct;
    path->light = path->light + path->through * direct;
    if (last)
        return false;
    ScatterMethod method = path->settings->path.scatter; // step 3: cosine sampling, drawn
    vec3 n = path->shadingNormal;
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
        LeaveSurface(path->scene, path->settings->methods, hit, dir, &path->ray, &path->from);
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

// rt's estimator, one vertex a turn: the emitted light of what the ray hit (weighted by MIS),
// then the bounce, until a miss, the depth cap, or roulette.
color FullPath(Path *path, bool foundFirst, const RayHit *firstHit) {
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
        if (node >= 0 && ((*log->tree)[node].found = found))
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
