// app/image_read.cpp -- reading images for --compare: PNG (through libpng's simplified API) and
// PPM, binary (P6, what rt writes) or plain text (P3, what many a first ray tracer prints), into
// 8-bit RGB. A file is read front to back, never sought, so a pipe serves as well as a file; and
// never past what the image its header describes can take, so an endless file (/dev/zero, a
// pipe that never closes) stops at that bound, and a header larger than rt's largest image
// (16384 x 16384, as --size and `size` allow) is refused before anything else is read.
#include "app.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <png.h>
#include <string>

// The longest side rt reads (or writes): as --size and `size` allow.
static const long kMostSide = 16384;

// Up to `most` more bytes of the file, appended to *bytes; *more is set where the file goes on
// past them. False with *why, strerror's words, for a read error (a directory opens, and fails
// here).
static bool ReadUpTo(FILE *file, size_t most, std::string *bytes, bool *more, std::string *why) {
    char chunk[1 << 16];
    for (size_t n; most > 0 && (n = fread(chunk, 1, std::min(most, sizeof chunk), file)) > 0;)
        bytes->append(chunk, n), most -= n;
    int next = most == 0 && !ferror(file) ? getc(file) : EOF; // (put back: only looked at)
    *more = next != EOF && ungetc(next, file) != EOF;
    if (ferror(file))
        *why = strerror(errno);
    return !ferror(file);
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
    if (png.width > kMostSide || png.height > kMostSide) {
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

// The most bytes a PNG of w x h pixels, `channels` samples of `depth` bits each, is read to:
// twice its rows uncompressed (a filter byte each), which no encoder's output reaches, and 16 MiB
// for its other chunks (text, colour profiles).
static size_t PngBound(uint32_t w, uint32_t h, int channels, int depth) {
    size_t row = 1 + ((size_t)w * (size_t)channels * (size_t)depth + 7) / 8;
    return 2 * row * (size_t)h + ((size_t)1 << 24);
}

// The rest of a PNG whose first bytes are read (its signature, at least): its header chunk IHDR
// first, whose size is refused if it is larger than rt's largest image, then the file up to the
// most that image can take (PngBound), then decoded. A file that goes on past that is refused.
static bool ReadPng(FILE *file, std::string *bytes, Image *image, std::string *why) {
    bool more;
    if (!ReadUpTo(file, 33 - std::min(bytes->size(), (size_t)33), bytes, &more, why))
        return false;
    const unsigned char *b = (const unsigned char *)bytes->data();
    if (bytes->size() < 33 || bytes->compare(12, 4, "IHDR") != 0) // (libpng says what is wrong)
        return DecodePng(*bytes, image, why);
    auto word = [b](int at) { // (most significant first)
        return (uint32_t)b[at] << 24 | (uint32_t)b[at + 1] << 16 | (uint32_t)b[at + 2] << 8 |
               b[at + 3];
    };
    uint32_t w = word(16), h = word(20);
    if (w > kMostSide || h > kMostSide) {
        *why = "a PNG of " + std::to_string(w) + " x " + std::to_string(h) + ", larger than rt's " +
               std::to_string(kMostSide) + " x " + std::to_string(kMostSide);
        return false;
    }
    const int kChannels[7] = {1, 4, 3, 1, 2, 4, 4}; // by colour type (2: RGB, 6: RGBA, ...)
    size_t bound = PngBound(w, h, b[25] < 7 ? kChannels[b[25]] : 4, b[24] <= 16 ? b[24] : 16);
    if (!ReadUpTo(file, bound - bytes->size(), bytes, &more, why))
        return false;
    if (more) {
        *why = "goes on past " + std::to_string(bound) + " bytes, more than a PNG of " +
               std::to_string(w) + " x " + std::to_string(h) + " can hold";
        return false;
    }
    return DecodePng(*bytes, image, why);
}

// A PPM as it is read: the bytes read ahead (`ahead`, from `at`), then the file; `used` counts
// every byte taken, and no byte is taken past `limit` (*beyond is then set: it reads as EOF).
struct PpmText {
    FILE *file;
    const std::string &ahead;
    size_t at, used, limit;
    bool beyond;
};
static int NextByte(PpmText *t) {
    if (t->used >= t->limit) {
        t->beyond = true;
        return EOF;
    }
    int c = t->at < t->ahead.size() ? (unsigned char)t->ahead[t->at++] : getc_unlocked(t->file);
    t->used += c != EOF;
    return c;
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

// How far a PPM is read: its header within the first 64 KiB (comments and all), then its samples
// alone: a binary one is one or two bytes; a plain one a number of up to five digits, and room
// for eleven bytes of white space beside it, more than any writer puts there.
static const size_t kPpmHeaderBytes = (size_t)1 << 16;
static const size_t kPlainSampleBytes = 16;

// A PPM (Netpbm's format), its magic number read: its width, height and largest sample, then the
// samples (PpmSample). They are taken as encoded values, as a PNG's are, and rescaled to 0..255,
// rounded to the nearest ((v 255 + most / 2) / most). The pixels grow as the samples are read, so
// a short file that claims 16384 x 16384 takes no 800 MB.
static bool DecodePpm(PpmText *t, bool plain, Image *image, std::string *why) {
    t->limit = kPpmHeaderBytes;
    long width = PpmNumber(t, kMostSide), height = PpmNumber(t, kMostSide);
    long most = PpmNumber(t, 65535);
    if (width < 1 || height < 1 || most < 1 || t->beyond) {
        *why = "not a PPM header rt can read (a width and a height of 1 to 16384, a largest "
               "sample of 1 to 65535, within the first 64 KiB)";
        return false;
    }
    size_t samples = (size_t)width * (size_t)height * 3;
    t->limit = t->used + samples * (plain ? kPlainSampleBytes : most > 255 ? 2 : 1);
    image->width = (int)width, image->height = (int)height;
    image->pixels.clear();
    image->pixels.reserve(std::min(samples, (size_t)1 << 20));
    for (size_t i = 0; i < samples; i++) {
        long v = PpmSample(t, plain, most);
        if (v < 0)
            break;
        image->pixels.push_back((unsigned char)((v * 255 + most / 2) / most));
    }
    if (t->beyond)
        *why = "goes on past " + std::to_string(t->limit) + " bytes without its " +
               std::to_string(width) + " x " + std::to_string(height) +
               " pixels, more than a plain PPM of that size holds";
    else if (image->pixels.size() < samples)
        *why = "the PPM ends before its " + std::to_string(width) + " x " + std::to_string(height) +
               " pixels, or holds a sample that is not a number up to " + std::to_string(most);
    return image->pixels.size() == samples && !t->beyond;
}

// What a file holds, by its first bytes: a PNG's signature, a PPM's magic number (then white
// space).
bool ReadImage(const char *path, Image *image, std::string *error) {
    static const char kPngSignature[] = "\x89PNG\r\n\x1a\n";
    std::string bytes, why;
    bool more, read = false;
    FILE *file = fopen(path, "rb");
    if (!file)
        why = strerror(errno);
    else if (!ReadUpTo(file, 8, &bytes, &more, &why))
        ;
    else if (bytes.empty())
        why = "an empty file, not an image";
    else if (bytes.compare(0, 8, kPngSignature, 8) == 0) {
        read = ReadPng(file, &bytes, image, &why);
    } else if (bytes.size() >= 3 && bytes[0] == 'P' && (bytes[1] == '6' || bytes[1] == '3') &&
               isspace((unsigned char)bytes[2])) {
        PpmText text = {file, bytes, 2, 2, 0, false};
        read = DecodePpm(&text, bytes[1] == '3', image, &why);
    } else
        why = "not a PNG or PPM image";
    if (file)
        fclose(file);
    if (!read)
        *error = std::string(path) + ": " + why;
    return read;
}
