// views.cpp -- debug views: what the primary rays found, drawn as colours instead of light.
//
// When the image looks wrong, these show which part is wrong: the normals (is a surface turned
// the right way?), the depth (is the camera where you think?), which object each pixel sees, how
// many rays each pixel cost, and the shadow mask (lit, blocked, or turned away from the light).
#include "ray.h"

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

// Per light: white if it lights the point, red if a shape blocks it, dark grey if the surface
// faces away from it; averaged over the lights. Uses the shading's own shadow test via AnyHit.
static color ShadowMask(const Scene *scene, const RenderSettings *settings, const RayHit *hit) {
    color sum = {0, 0, 0};
    for (const Light &light : scene->lights) {
        vec3 toLight = light.position - hit->point;
        if (!(Dot(hit->normal, toLight) > 0)) {
            sum = sum + color{0.25, 0.25, 0.25};
            continue;
        }
        Ray shadow;
        RayStart start;
        bool blocked = ShadowRay(hit, light.position, &settings->methods, &shadow, &start) &&
                       AnyHitFrom(scene, settings->methods, &shadow, &start, 1);
        sum = sum + (blocked ? color{1, 0, 0} : color{1, 1, 1});
    }
    return scene->lights.empty() ? sum : (real(1) / scene->lights.size()) * sum;
}

// The raw value of one pixel; depth and cost are scaled to the image's range afterwards.
static color ViewValue(const Scene *scene, const RenderSettings *settings, ViewKind view, int i,
                       int j, real *scalar) {
    Ray ray;
    GetCameraRay(&settings->camera, settings->width, settings->height, SamplePosition(i, j, 0, 1),
                 &ray);
    if (view == VIEW_COST) {
        RayStats stats = {};
        TraceLog log = {stats, nullptr, -1, 0};
        TraceRay(scene, settings, RAY_PRIMARY, &ray, &kFromTheEye, RayChain{1, 1}, &log);
        *scalar = real(log.stats.primary + log.stats.shadow + log.stats.reflection +
                       log.stats.refraction);
        return {0, 0, 0};
    }
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
        return ShadowMask(scene, settings, &hit);
    return {0, 0, 0};
}

void RenderView(const Scene *scene, const RenderSettings *settings, ViewKind view, Image *image) {
    int w = settings->width, h = settings->height;
    std::vector<color> colors((size_t)w * h);
    std::vector<real> scalars((size_t)w * h);
    for (int j = 0; j < h; j++)
        for (int i = 0; i < w; i++)
            colors[(size_t)j * w + i] =
                ViewValue(scene, settings, view, i, j, &scalars[(size_t)j * w + i]);

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
