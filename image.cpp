// image.cpp -- PNG files, through libpng's simplified API (png_image, libpng 1.6).
//
// An image is written to a temporary file beside the target and renamed over it only when the
// whole file is on disk, so a failed or interrupted run never leaves a broken or half-written
// image, and an existing file stays exactly as it was.
#include "ray.h"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <png.h>
#include <sys/stat.h>
#include <unistd.h>

// Compression: PNG_IMAGE_FLAG_FAST (no row filters, zlib level 3 in libpng 1.6) instead of the
// default (adaptive filters, zlib level 6). Measured on the assignment image (README, "PNG
// compression"): the default costs about as much as the whole render, the fast setting a
// fraction of it, and the assignment image's flat colours still compress well.
static const png_uint_32 kPngFlags = PNG_IMAGE_FLAG_FAST;

bool WritePng(const char *path, const Image *image, std::string *error) {
    std::string temporary = std::string(path) + ".XXXXXX";
    int fd = mkstemp(&temporary[0]);
    if (fd < 0) {
        *error = std::string(path) + ": " + strerror(errno);
        return false;
    }
    FILE *file = fdopen(fd, "wb");
    if (!file) {
        *error = std::string(path) + ": " + strerror(errno);
        close(fd);
        unlink(temporary.c_str());
        return false;
    }

    png_image png;
    memset(&png, 0, sizeof png);
    png.version = PNG_IMAGE_VERSION;
    png.width = (png_uint_32)image->width;
    png.height = (png_uint_32)image->height;
    png.format = PNG_FORMAT_RGB;
    png.flags = kPngFlags;
    bool written = png_image_write_to_stdio(&png, file, 0, image->pixels.data(), 0, nullptr) != 0;
    if (!written)
        *error = std::string(path) + ": " + png.message;
    png_image_free(&png);

    // fclose flushes; a full disk shows up here, not earlier
    if (fclose(file) != 0 && written) {
        *error = std::string(path) + ": " + strerror(errno);
        written = false;
    }
    // mkstemp creates the file readable by its owner only; give it the usual permissions
    if (written) {
        mode_t mask = umask(0);
        umask(mask);
        chmod(temporary.c_str(), 0666 & ~mask);
    }
    if (written && rename(temporary.c_str(), path) != 0) {
        *error = std::string(path) + ": " + strerror(errno);
        written = false;
    }
    if (!written)
        unlink(temporary.c_str());
    return written;
}

bool ReadPng(const char *path, Image *image, std::string *error) {
    png_image png;
    memset(&png, 0, sizeof png);
    png.version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_file(&png, path)) {
        *error = std::string(path) + ": " + png.message;
        return false;
    }
    // Any PNG is converted to 8-bit RGB; alpha is dropped against a black background
    png.format = PNG_FORMAT_RGB;
    image->width = (int)png.width;
    image->height = (int)png.height;
    image->pixels.assign(PNG_IMAGE_SIZE(png), 0);
    if (!png_image_finish_read(&png, nullptr, image->pixels.data(), 0, nullptr)) {
        *error = std::string(path) + ": " + png.message;
        png_image_free(&png);
        return false;
    }
    return true;
}

// A heat scale for x in [0, 1]: black, red, yellow, white, each channel rising in turn.
color HeatColor(real x) {
    x = std::fmin(real(1), std::fmax(real(0), x)) * 3;
    return {std::fmin(x, real(1)), std::fmin(std::fmax(x - 1, real(0)), real(1)),
            std::fmin(std::fmax(x - 2, real(0)), real(1))};
}

bool CompareImages(const Image *a, const Image *b, int tolerance, ImageDifference *difference,
                   Image *heatmap) {
    if (a->width != b->width || a->height != b->height)
        return false;
    size_t pixels = (size_t)a->width * a->height;
    heatmap->width = a->width;
    heatmap->height = a->height;
    heatmap->pixels.assign(pixels * 3, 0);
    double sumSquares = 0;
    *difference = ImageDifference{0, 0, 0, 0};
    for (size_t p = 0; p < pixels; p++) {
        int largest = 0;
        for (int c = 0; c < 3; c++) {
            int d = std::abs((int)a->pixels[3 * p + c] - (int)b->pixels[3 * p + c]);
            sumSquares += (double)d * d;
            largest = std::max(largest, d);
        }
        difference->largest = std::max(difference->largest, largest);
        difference->pixelsOver += largest > tolerance;
        color heat = HeatColor(real(largest) / 255);
        heatmap->pixels[3 * p + 0] = ToByte(heat.x);
        heatmap->pixels[3 * p + 1] = ToByte(heat.y);
        heatmap->pixels[3 * p + 2] = ToByte(heat.z);
    }
    difference->rmse = std::sqrt(sumSquares / (3.0 * (double)std::max(pixels, (size_t)1)));
    difference->psnr = difference->rmse > 0 ? 20 * std::log10(255 / difference->rmse) : INFINITY;
    return true;
}
