// app/image_read.cpp -- reading images for --compare: PNG (through libpng's simplified API) and
// PPM, binary (P6, what rt writes) or plain text (P3, what many a first ray tracer prints), into
// 8-bit RGB. A file is read whole first, front to back, so a pipe serves as well as a file.
#include "app.h"

#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <png.h>
#include <string>

// The whole of a file, read front to back (so a pipe, /dev/stdin or a shell's <(...) serve too:
// nothing is sought). False with *why, strerror's words (a directory opens, and fails here).
static bool ReadAll(const char *path, std::string *bytes, std::string *why) {
    FILE *file = fopen(path, "rb");
    if (!file) {
        *why = strerror(errno);
        return false;
    }
    char chunk[1 << 16];
    bytes->clear();
    for (size_t n; (n = fread(chunk, 1, sizeof chunk, file)) > 0;)
        bytes->append(chunk, n);
    bool read = !ferror(file);
    if (!read)
        *why = strerror(errno);
    fclose(file);
    return read;
}

// A PNG converted to 8-bit RGB: a pixel with alpha is composited over black, in linear light, as
// libpng does it (RGBA 200 100 50 128 becomes 148 73 34). A 16-bit PNG that
// does not say how it is encoded is taken as sRGB, as an 8-bit one is (libpng would take it as
// linear light and re-encode it, 200/255 becoming 228/255), so that it compares equal to the
// 8-bit file of the same colours.
static bool DecodePng(const std::string &bytes, Image *image, std::string *why) {
    png_image png;
    memset(&png, 0, sizeof png);
    png.version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_memory(&png, bytes.data(), bytes.size())) {
        *why = png.message;
        return false;
    }
    if (png.width > 16384 || png.height > 16384) { // (as --size and `size` allow)
        *why = "a PNG of " + std::to_string(png.width) + " x " + std::to_string(png.height) +
               ", larger than rt's 16384 x 16384";
        png_image_free(&png);
        return false;
    }
    png.flags |= PNG_IMAGE_FLAG_16BIT_sRGB;
    png.format = PNG_FORMAT_RGB;
    image->width = (int)png.width;
    image->height = (int)png.height;
    image->pixels.assign(PNG_IMAGE_SIZE(png), 0);
    if (!png_image_finish_read(&png, nullptr, image->pixels.data(), 0, nullptr)) {
        *why = png.message;
        png_image_free(&png);
        return false;
    }
    return true;
}

// A PPM's bytes and how far they have been read.
struct PpmText {
    const std::string &bytes;
    size_t at;
};
static int NextByte(PpmText *t) {
    return t->at < t->bytes.size() ? (unsigned char)t->bytes[t->at++] : EOF;
}

// The next number of a PPM: decimal digits after white space and `#` comments, ended by white
// space, a comment (which Netpbm allows straight after a number: `4#wide`) or the end of the
// file; -1 where there is none, or it is larger than `most`. A comment that ends the largest
// sample of a P6 header also ends the header: the samples start on the next line.
static long PpmNumber(PpmText *t, long most) {
    int c = NextByte(t);
    for (;;) {
        while (c != EOF && isspace(c))
            c = NextByte(t);
        if (c != '#')
            break;
        while (c != EOF && c != '\n' && c != '\r') // (a comment ends at either, as in Netpbm)
            c = NextByte(t);
    }
    long n = 0;
    if (!isdigit(c))
        return -1;
    for (; c != EOF && isdigit(c); c = NextByte(t))
        if ((n = 10 * n + (c - '0')) > most)
            return -1;
    if (c == '#') // a comment to the end of its line, whose end is then the white space read
        while (c != EOF && c != '\n' && c != '\r')
            c = NextByte(t);
    return c == EOF || isspace(c) ? n : -1; // (the one white space after a P6 header read)
}

// The next sample of a PPM: a decimal number (P3, `plain`), or one byte, two when the largest
// sample is above 255, the most significant first (P6); -1 where there is none up to `most`.
static long PpmSample(PpmText *t, bool plain, long most) {
    if (plain)
        return PpmNumber(t, most);
    long v = NextByte(t);
    if (most > 255 && v != EOF) {
        int low = NextByte(t);
        v = low == EOF ? -1 : v << 8 | low;
    }
    return v <= most ? v : -1; // (EOF is -1: a file cut short)
}

// A PPM (Netpbm's format): its magic number, width, height and largest sample, then the samples
// (PpmSample). They are taken as encoded values, as a PNG's are, and rescaled to 0..255, rounded
// to the nearest ((v 255 + most / 2) / most). The pixels are made only once the file is known to
// be long enough to hold them, so a short file that claims 16384 x 16384 takes no 800 MB.
static bool DecodePpm(const std::string &bytes, Image *image, std::string *why) {
    const long kMostSide = 16384; // as --size and `size` allow
    PpmText t = {bytes, 2};
    bool plain = bytes[1] == '3';
    long width = PpmNumber(&t, kMostSide), height = PpmNumber(&t, kMostSide);
    long most = PpmNumber(&t, 65535);
    if (width < 1 || height < 1 || most < 1) {
        *why = "not a PPM header rt can read (a width and a height of 1 to 16384, a largest "
               "sample of 1 to 65535)";
        return false;
    }
    // The fewest bytes the samples can take: a binary sample one or two; a plain one a digit
    // and a space, but the last
    size_t samples = (size_t)width * (size_t)height * 3;
    size_t fewest = plain ? 2 * samples - 1 : (most > 255 ? 2 : 1) * samples;
    bool read = bytes.size() - t.at >= fewest;
    if (read) {
        image->width = (int)width, image->height = (int)height;
        image->pixels.assign(samples, 0);
    }
    for (size_t i = 0; i < samples && read; i++) {
        long v = PpmSample(&t, plain, most);
        if ((read = v >= 0))
            image->pixels[i] = (unsigned char)((v * 255 + most / 2) / most);
    }
    if (!read)
        *why = "the PPM ends before its " + std::to_string(width) + " x " + std::to_string(height) +
               " pixels, or holds a sample that is not a number up to " + std::to_string(most);
    return read;
}

// What the bytes of a file hold, by their first bytes: a PNG's signature, a PPM's magic number.
static bool DecodeImage(const std::string &bytes, Image *image, std::string *why) {
    static const char kPngSignature[] = "\x89PNG\r\n\x1a\n";
    if (bytes.empty())
        *why = "an empty file, not an image";
    else if (bytes.compare(0, 8, kPngSignature, 8) == 0)
        return DecodePng(bytes, image, why);
    else if (bytes.size() >= 3 && bytes[0] == 'P' && (bytes[1] == '6' || bytes[1] == '3') &&
             isspace((unsigned char)bytes[2])) // (the magic number, then white space)
        return DecodePpm(bytes, image, why);
    else
        *why = "not a PNG or PPM image";
    return false;
}

bool ReadImage(const char *path, Image *image, std::string *error) {
    std::string bytes, why;
    bool read = ReadAll(path, &bytes, &why) && DecodeImage(bytes, image, &why);
    if (!read)
        *error = std::string(path) + ": " + why;
    return read;
}
