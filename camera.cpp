// camera.cpp -- the cameras: where each pixel's ray starts and where it goes.
//
// The assignment handout's GetRay(Perspective, vec2, Ray*), the second handout's screen camera
// (eye e, screen corner l, edges h and v), and the scene files' lookat camera, turned into the
// screen form once per render (PlanRender, render.cpp). Every direction is built from the eye
// outward, so it does not depend on how far the eye is from the origin.
#include "ray.h"

#include <algorithm>
#include <cmath>

// The screen lies `distance` in front of the eye (at z = eye.z - distance), centred on the line
// of sight, p.screenWidth wide, with square pixels of size screenWidth / widthPixels; screen x
// grows to the right and y grows up, while screenCoord.y counts pixel rows down from the top.
// Checked by TestGetRay (tests/test_handout.cpp).
void GetRay(Perspective p, vec2 screenCoord, Ray *ray) {
    real pixelSize = p.screenWidth / p.widthPixels;
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
    if (camera->lensRadius > 0) // beyond the handouts: the book's thin lens (blur.cpp; GetLensRay)
        return GetLensCameraRay(camera, width, height, screenCoord, ray);
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
// the eye (toCorner), so a camera 1e30 from the origin does too. The lens disk lies in the plane
// of u and v, as the book's defocus_disk_u and defocus_disk_v.
bool LookAtToScreen(const Camera *camera, int width, int height, Camera *screen,
                    std::string *error) {
    vec3 w = SafeNormalize(camera->lookFrom - camera->lookAt);
    vec3 u = SafeNormalize(Cross(SafeNormalize(camera->vup), w));
    real fov = camera->fovDegrees;
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
    *screen = *camera;
    screen->kind = CAMERA_SCREEN;
    screen->eye = camera->lookFrom;
    screen->toCorner = -w - halfWidth * u - halfHeight * v;
    screen->lowerLeft = camera->lookFrom + screen->toCorner;
    screen->horizontal = (2 * halfWidth) * u;
    screen->vertical = (2 * halfHeight) * v;
    screen->lensU = camera->lensRadius * u;
    screen->lensV = camera->lensRadius * v;
    return true;
}

// Ray Tracing in One Weekend's thin lens (§13, Defocus Blur): a ray starts at a point of the lens
// disk and goes through the pixel's point on the plane in focus, so all the rays of a point of
// that plane meet there, and a point nearer or farther is spread over a disk (the circle of
// confusion). The pinhole's direction d reaches the screen, one unit in front of the eye, at
// t = 1; the plane in focus is focusDistance in front, at eye + focusDistance d. From the lens
// point eye + offset, the direction is that point minus the offset, built from the eye outward
// (as every direction here) so that no coordinate of the eye's position enters it.
void GetLensRay(const Camera *camera, int width, int height, vec2 screenCoord, vec2 lens,
                Ray *ray) {
    GetScreenRay(camera, width, height, screenCoord, ray);
    vec3 offset = lens.x * camera->lensU + lens.y * camera->lensV;
    ray->origin = ray->origin + offset;
    ray->dir = camera->focusDistance * ray->dir - offset;
    if (camera->fromScreen) { // the slides' ray starts on the screen, one unit in front of the lens
        ray->origin = ray->origin + (1 / camera->focusDistance) * ray->dir;
        ray->dir = SafeNormalize(ray->dir);
    }
}
