// app/views.cpp -- debug views: what the primary rays found, drawn as colours instead of light.
//
// When the image looks wrong, these show which part is wrong: the normals (is a surface turned
// the right way?), the depth (is the camera where you think?), which object each pixel sees, how
// many rays each pixel cost, and the shadow mask (lit, blocked, or turned away from the light).
#include "app.h"

#include <algorithm>

static const struct {
    const char *name;
    ViewKind view;
} kViews[] = {{"normal", VIEW_NORMAL},
              {"depth", VIEW_DEPTH},
              {"id", VIEW_ID},
              {"cost", VIEW_COST},
              {"shadow", VIEW_SHADOW}};

const char *ViewName(ViewKind view) {
    for (const auto &v : kViews)
        if (v.view == view)
            return v.name;
    return "view";
}

bool FindView(const std::string &name, ViewKind *view) {
    for (const auto &v : kViews) {
        if (name == v.name) {
            *view = v.view;
            return true;
        }
    }
    return false;
}

// A distinct, stable colour for each shape: hues spread by the golden ratio, spheres brighter.
static color ShapeColor(const RayHit *hit) {
    real hue = std::fmod(real(0.618034) * (hit->index + 1) + (hit->shape == SHAPE_SPHERE ? 0 : 0.3),
                         real(1)) *
               6;
    real x = 1 - std::fabs(std::fmod(hue, real(2)) - 1);
    color rgb[6] = {{1, x, 0}, {x, 1, 0}, {0, 1, x}, {0, x, 1}, {x, 0, 1}, {1, 0, x}};
    real level = hit->shape == SHAPE_SPHERE ? 1 : real(0.7);
    return level * rgb[std::min(5, (int)hue)];
}

// Whether a light lights the point (1), is blocked by a shape (0), or is behind the surface (-1),
// by the shading's own shadow test.
static int LightState(const Scene *scene, const RenderSettings *settings, const RayHit *hit,
                      const Light *light, RayStats *stats) {
    if (!(Dot(hit->normal, light->position - hit->point) > 0))
        return -1;
    Ray shadow;
    SelfHit from;
    if (!ShadowRay(scene, settings->methods, hit, light->position, &shadow, &from))
        return 1; // the light is at the point itself: nothing between them
    stats->shadow++;
    return AnyHitFrom(scene, settings->methods, &shadow, &from, 1) ? 0 : 1;
}

// One light: white if it lights the point, red if a shape blocks it, dark grey if the surface
// faces away from it. Several: each of the first three lights in its own channel (red, green,
// blue), full where it lights the point, 0.45 where a shape blocks it, none where the surface
// faces away, so every combination has its own colour (a fourth light on is not shown).
static color ShadowMask(const Scene *scene, const RenderSettings *settings, const RayHit *hit,
                        RayStats *stats) {
    if (scene->lights.size() == 1) {
        int state = LightState(scene, settings, hit, &scene->lights[0], stats);
        return state > 0 ? color{1, 1, 1} : state == 0 ? color{1, 0, 0} : color{0.25, 0.25, 0.25};
    }
    real channel[3] = {0, 0, 0};
    for (size_t k = 0; k < 3 && k < scene->lights.size(); k++) {
        int state = LightState(scene, settings, hit, &scene->lights[k], stats);
        channel[k] = state > 0 ? 1 : state == 0 ? real(0.45) : 0;
    }
    return {channel[0], channel[1], channel[2]};
}

// Every ray counted in *s.
static uint64_t RaysCast(const RayStats *s) {
    return s->primary + s->shadow + s->reflection + s->refraction + s->diffuse;
}

// The raw value of one pixel; depth and cost are scaled to the image's range afterwards. The
// rays it casts are counted in *stats.
static color ViewValue(const Scene *scene, const RenderSettings *settings, ViewKind view, int i,
                       int j, real *scalar, RayStats *stats) {
    Ray ray;
    GetCameraRay(&settings->camera, settings->width, settings->height, SamplePosition(i, j, 0, 1),
                 &ray);
    if (view == VIEW_COST) {
        TraceLog log = {*stats, nullptr, -1, 0}; // counting on from the pixels before
        TraceRay(scene, settings, RAY_PRIMARY, &ray, &kNoSelfHit, RayChain{1, 1}, &log);
        *scalar = real(RaysCast(&log.stats) - RaysCast(stats));
        *stats = log.stats;
        return {0, 0, 0};
    }
    stats->primary++;
    RayHit hit;
    *scalar = -1; // no hit
    if (!FindNearestHit(scene, settings->methods, &ray, 0, kInfinity, &hit))
        return {0, 0, 0};
    *scalar = hit.t * SafeLength(ray.dir); // distance from where the ray starts (eye or screen)
    if (view == VIEW_NORMAL)
        return real(0.5) * (hit.normal + vec3{1, 1, 1});
    if (view == VIEW_ID)
        return ShapeColor(&hit);
    if (view == VIEW_SHADOW)
        return ShadowMask(scene, settings, &hit, stats);
    return {0, 0, 0};
}

void RenderView(const Scene *scene, const RenderSettings *settings, ViewKind view, Image *image,
                RayStats *stats) {
    int w = settings->width, h = settings->height;
    std::vector<color> colors((size_t)w * h);
    std::vector<real> scalars((size_t)w * h);
    for (int j = 0; j < h; j++)
        for (int i = 0; i < w; i++)
            colors[(size_t)j * w + i] =
                ViewValue(scene, settings, view, i, j, &scalars[(size_t)j * w + i], stats);

    // Depth: nearest hit white, farthest dark grey, misses black. Cost: a heat scale from 0 rays
    // to the most any pixel cost.
    real lo = kInfinity, hi = 0;
    for (real s : scalars)
        if (s >= 0) {
            lo = std::min(lo, s);
            hi = std::max(hi, s);
        }
    for (size_t p = 0; p < colors.size(); p++) {
        real s = scalars[p];
        if (view == VIEW_DEPTH && s >= 0) {
            real shade = hi > lo ? 1 - real(0.8) * (s - lo) / (hi - lo) : 1;
            colors[p] = {shade, shade, shade};
        }
        if (view == VIEW_COST)
            colors[p] = HeatColor(hi > 0 ? s / hi : 0);
    }
    image->width = w;
    image->height = h;
    image->pixels.resize(colors.size() * 3);
    for (size_t p = 0; p < colors.size(); p++) {
        image->pixels[3 * p + 0] = ToByte(colors[p].x);
        image->pixels[3 * p + 1] = ToByte(colors[p].y);
        image->pixels[3 * p + 2] = ToByte(colors[p].z);
    }
}
