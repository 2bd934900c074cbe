// camera.cpp -- the cameras: where each pixel's ray starts and where it goes.
//
// The assignment handout's GetRay(Perspective, vec2, Ray*), the second handout's screen camera
// (eye e, screen corner l, edges h and v), and the scene files' lookat camera, turned into the
// screen form once per render (PlanRender). Every direction is built from the eye outward, so
// it does not depend on how far the eye is from the origin.
#include "ray.h"
#include "render.h"

#include <algorithm>
#include <cmath>

// The screen lies `distance` in front of the eye (at z = eye.z - distance), centred on the line
// of sight, width p.width, with square pixels of size width / widthPixels; screen x grows to the
// right and y grows up, while screenCoord.y counts pixel rows down from the top.
void GetRay(Perspective p, vec2 screenCoord, Ray *ray) {
    real pixelSize = p.width / p.widthPixels;
    real x = (screenCoord.x - real(0.5) * p.widthPixels) * pixelSize;
    real y = (real(0.5) * p.heightPixels - screenCoord.y) * pixelSize;
    ray->origin = p.eye;            // handout: the pixel's point on the screen (see GetCameraRay)
    ray->dir = {x, y, -p.distance}; // handout: normalize(pixel - camera)
}

// The second handout's screen: pixel centres l + (i + .5)/W h + (j + .5)/H v with j counted
// from the bottom; an image row y counts from the top, so the vertical fraction is (H - y) / H.
// The direction is built from the corner as seen from the eye, l - e (PlanRender), not from l:
// with the eye 1e15 from the origin, l + ... - e would lose the screen to rounding.
void GetScreenRay(const Camera *camera, int width, int height, vec2 screenCoord, Ray *ray) {
    real across = screenCoord.x / width, up = (height - screenCoord.y) / height;
    ray->origin = camera->eye;
    ray->dir = camera->toCorner + across * camera->horizontal + up * camera->vertical;
}

// The slides' GetRay (`--methods handout`): Position = the pixel's point on the screen,
// Vector = normalize(pixel - camera). rt's own starts at the eye with the unnormalised vector
// eye -> pixel (the second handout's form): t = 1 is then the screen, and a shape between the eye
// and the screen is still seen.
void GetCameraRay(const Camera *camera, int width, int height, vec2 screenCoord, Ray *ray) {
    if (camera->kind == CAMERA_PERSPECTIVE)
        GetRay(camera->perspective, screenCoord, ray);
    else
        GetScreenRay(camera, width, height, screenCoord, ray);
    if (camera->fromScreen) {
        ray->origin = ray->origin + ray->dir;
        ray->dir = SafeNormalize(ray->dir);
    }
}

// An orthonormal frame at the eye: w points back from the view, u right, v up (FCG §4.3). The
// screen stands one unit in front of the eye, tan(fov / 2) high above the centre, and as wide as
// the image's aspect ratio makes it (square pixels). Every vector is normalised after rescaling
// (SafeNormalize), so a camera 1e200 from its target works, and the corner is kept relative to
// the eye (toCorner), so a camera 1e30 from the origin does too.
bool LookAtToScreen(const Camera *lookAt, int width, int height, Camera *screen,
                    std::string *error) {
    vec3 w = SafeNormalize(lookAt->from - lookAt->to);
    vec3 u = SafeNormalize(Cross(SafeNormalize(lookAt->up), w));
    real fov = lookAt->fovDegrees;
    if (!(MaxComponent(w) > 0) || !IsFinite(w)) {
        *error = "from and to are the same point (or too far apart to subtract)";
        return false;
    }
    if (!(MaxComponent(u) > 0) || !IsFinite(u)) {
        *error = "up is zero or along the view direction";
        return false;
    }
    if (!(fov > 0 && fov < 180)) {
        *error = "the field of view must be more than 0 and less than 180 degrees";
        return false;
    }
    vec3 v = Cross(w, u);
    real halfHeight = std::tan(fov * real(M_PI / 360)), halfWidth = halfHeight * width / height;
    *screen = *lookAt;
    screen->kind = CAMERA_SCREEN;
    screen->eye = lookAt->from;
    screen->toCorner = -w - halfWidth * u - halfHeight * v;
    screen->lowerLeft = lookAt->from + screen->toCorner;
    screen->horizontal = (2 * halfWidth) * u;
    screen->vertical = (2 * halfHeight) * v;
    return true;
}

bool ScreenCameraIsValid(const Camera *c, std::string *error) {
    vec3 h = SafeNormalize(c->horizontal), v = SafeNormalize(c->vertical), hxv = Cross(h, v);
    // |h x v| of the unit edges is the sine of their angle, known only to a few roundings: each
    // unit vector's components are within about 2 u of the exact ones (4 u for the two), and
    // the products and the subtraction add 3 u: 7 u, taken as 8. Below that the edges may as
    // well be parallel (their screen has no height that rounding can tell from none: every row
    // of pixels would be the same)
    vec3 normal = SafeNormalize(hxv);
    if (!(Length(hxv) > 8 * kUnitRoundoff) || !IsFinite(normal)) {
        *error = "the edges h and v must be non-zero and not parallel";
        return false;
    }
    vec3 toCorner = c->lowerLeft - c->eye;
    if (!IsFinite(Abs(toCorner) + Abs(c->horizontal) + Abs(c->vertical))) {
        *error = "the screen is so large that a pixel's direction would overflow";
        return false;
    }
    if (!(std::fabs(Dot(normal, SafeNormalize(toCorner))) > 0)) {
        *error = "the eye lies on the screen's plane (or is too far from it to subtract), so no "
                 "ray can pass through the screen";
        return false;
    }
    return true;
}

void PlanRender(const Scene *scene, RenderSettings *settings) {
    PlanEffects(scene, settings, &settings->effects);
    settings->camera = scene->camera;
    settings->camera.perspective.widthPixels = settings->width;
    settings->camera.perspective.heightPixels = settings->height;
    settings->camera.toCorner = scene->camera.lowerLeft - scene->camera.eye;
    std::string unused;
    if (scene->camera.kind == CAMERA_LOOKAT) // checked when the scene was read
        LookAtToScreen(&scene->camera, settings->width, settings->height, &settings->camera,
                       &unused);
    settings->camera.fromScreen = settings->methods.cameraRay == CAMERA_RAY_SLIDES;
}

// ---- a screen camera's shape ----------------------------------------------------------------

// A screen camera's edges fix its shape, so the image must keep it, or the pixels would not be
// square and spheres would come out as eggs: W : H must be |h| : |v| to within 1 part in 256
// (less than a pixel's width across 256 pixels). A perspective or lookat camera adapts its
// screen to the image instead.
bool SquarePixels(double W, double H, double h, double v) {
    double longer = std::max(h, v); // (edges of 1e308 rescaled first: W v would overflow)
    if (longer > 0 && std::isfinite(longer))
        h /= longer, v /= longer;
    return std::fabs(W * v - H * h) <= (W * v + H * h) / 512;
}

// A size that keeps the screen's pixels square: `width` wide, or, when no whole height fits that
// width (a 3 x 1 screen 100 pixels wide would need 33.3 rows), the nearest width that has one
// (99, with 33 rows; 33 x 24 asked of a 4 x 3 screen gives 32 x 24). A width's height is the
// nearest whole one, or the limit where that is beyond it (within 1 part in 256, the limit
// itself may fit). False when no size within the limit (16384) fits.
bool SquareSize(int width, double h, double v, int *W, int *H) {
    const int kMaxSide = 16384; // as --size and `size` allow
    for (int away = 0; away < kMaxSide; away++)
        for (int w : {width - away, width + away}) { // (the narrower first)
            double exact = w * (v / h); // (v / h first: w v may overflow where v / h does not)
            int height = exact >= kMaxSide ? kMaxSide : std::max(1, (int)std::lround(exact));
            if (w >= 1 && w <= kMaxSide && SquarePixels(w, height, h, v)) {
                *W = w, *H = height;
                return true;
            }
        }
    return false;
}

// The cosine of the edges' angle above 1/256, the tolerance SquarePixels allows the proportions:
// a pixel's corner more than about a quarter of a degree from a right angle. (SafeNormalize:
// edges of 1e-310 or 1e300 have the angle they have at 1.)
bool ScreenIsSheared(const Camera *camera) {
    vec3 h = SafeNormalize(camera->horizontal), v = SafeNormalize(camera->vertical);
    return std::fabs(Dot(h, v)) > real(1) / 256;
}
