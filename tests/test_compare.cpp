// tests/test_compare.cpp -- `ray --compare` from the outside: PNG and PPM (binary and plain,
// any largest sample, through a pipe), exit 0 within the tolerance and 1 outside it, a heat map
// with -o, and every file it cannot read refused with a message that says why.
#include "../app/app.h"
#include "test.h"

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <string>

// The four bytes of n, the most significant first (PNG's order).
static std::string BigEndian(uint32_t n) {
    return {(char)(n >> 24), (char)(n >> 16), (char)(n >> 8), (char)n};
}

// A PNG chunk: its length, its type and data, and their CRC-32 (the PNG specification's, bit by
// bit).
static std::string PngChunk(const std::string &type, const std::string &data) {
    uint32_t crc = 0xffffffffu;
    for (unsigned char b : type + data) {
        crc ^= b;
        for (int k = 0; k < 8; k++)
            crc = crc & 1 ? (crc >> 1) ^ 0xedb88320u : crc >> 1;
    }
    return BigEndian((uint32_t)data.size()) + type + data + BigEndian(~crc);
}

// A PNG's first chunks, claiming 30000 x 30000 pixels and holding none: IHDR (8-bit RGB) and an
// empty IDAT.
static std::string HugePngHeader() {
    std::string size = BigEndian(30000) + BigEndian(30000);
    return std::string("\x89PNG\r\n\x1a\n", 8) +
           PngChunk("IHDR", size + std::string("\x08\x02\x00\x00\x00", 5)) + PngChunk("IDAT", "");
}

// --compare reads PPM as well as PNG: rt's own .ppm, and the plain text P3 that a student's first
// ray tracer may print, each the same picture as rt's PNG. A file that is no image, or is cut
// short, is exit 2 with a message saying which.
static void TestComparePpm(const std::string &dir) {
    std::string err;
    RunRay(dir, "--size 4 -o four.png", &err), RunRay(dir, "--size 4 -o four.ppm", &err);
    CHECK(RunRay(dir, "--compare four.png four.ppm", &err) == 0 &&
              ReadOutput(dir).find("largest difference: 0") != std::string::npos,
          "--compare of rt's PNG with its PPM: the same picture, exit 0 (" + err + ")");
    Image four;
    std::string readError;
    if (!ReadImage((dir + "/four.png").c_str(), &four, &readError))
        return;
    std::string plain = "P3\n# a student's image\n4 4\n255\n", fifteen = "P3 4#wide\n4 15 ";
    std::string wide = "P6 4 4 65535# comments end numbers, and this one the header\r";
    for (unsigned char v : four.pixels) {
        plain += std::to_string(v) + (plain.size() % 60 < 4 ? "\n" : " ");
        fifteen += std::to_string((v * 15 + 127) / 255) + " "; // rounded to 0..15
        wide += std::string(2, (char)v);                       // v * 257, most significant first
    }
    std::ofstream(dir + "/plain.ppm") << plain;
    std::ofstream(dir + "/fifteen.ppm") << fifteen;
    std::ofstream(dir + "/wide.ppm", std::ios::binary) << wide;
    std::string wideLf = wide; // the same, the comment ended by LF
    wideLf[wideLf.find('\r')] = '\n';
    std::ofstream(dir + "/widelf.ppm", std::ios::binary) << wideLf;
    std::ofstream(dir + "/cut.ppm") << plain.substr(0, plain.size() - 8);
    CHECK(RunRay(dir, "--compare four.png plain.ppm", &err) == 0,
          "a plain (P3) PPM with a comment: the same picture, exit 0 (" + err + ")");
    CHECK(RunRayAfter(dir, "cat four.png |", "--compare four.png /dev/stdin", &err) == 0 &&
              RunRayAfter(dir, "cat plain.ppm |", "--compare four.png /dev/stdin", &err) == 0,
          "a PNG and a PPM read from a pipe (nothing sought): the same picture (" + err + ")");
    CHECK(RunRay(dir, "--compare four.png wide.ppm", &err) == 0 &&
              RunRay(dir, "--compare four.png widelf.ppm", &err) == 0,
          "a P6 PPM of 16-bit samples, a comment straight after its header ended by CR or LF: "
          "rescaled to the same picture, exit 0 (" +
              err + ")");
    CHECK(RunRay(dir, "--compare four.png fifteen.ppm --tolerance 9", &err) == 0 &&
              ReadOutput(dir).find("largest difference: 0\n") == std::string::npos,
          "samples of 0..15 (a comment straight after the width): rescaled, within 255 / 15 / 2 "
          "levels, not equal (" +
              err + ")");
    std::ofstream(dir + "/text.png") << "not an image\n";
    std::ofstream(dir + "/nothing.png");
    const struct {
        const char *file, *message;
    } bad[] = {{"cut.ppm", "cut.ppm: the PPM ends before its 4 x 4 pixels"},
               {"text.png", "text.png: not a PNG or PPM image"},
               {"nothing.png", "nothing.png: an empty file, not an image"},
               {".", ".: Is a directory"},
               {"huge.ppm", "huge.ppm: the PPM ends before its 16384 x 16384 pixels"},
               {"huge.png", "huge.png: a PNG of 30000 x 30000, larger than rt's 16384 x 16384"},
               {"P36.ppm", "P36.ppm: not a PNG or PPM image"}};
    std::ofstream(dir + "/P36.ppm") << "P36 1 1\n255 255 255\n";  // (no space after the magic)
    std::ofstream(dir + "/huge.ppm") << "P6\n16384 16384\n255\n"; // (no 800 MB made for it)
    std::ofstream(dir + "/huge.png", std::ios::binary) << HugePngHeader(); // (nor 2.7 GB)
    for (const auto &b : bad)
        CHECK(RunRay(dir, "--compare four.png " + std::string(b.file), &err) == 2 &&
                  err.find(b.message) != std::string::npos,
              std::string("--compare with ") + b.file + ": exit 2, " + b.message + " (" + err +
                  ")");
}

// --compare names the pixels that differ most, so that `--pixel X Y` can be asked about them:
// three pixels changed by hand in a 4 x 3 plain PPM, by 9, 200 and 9 levels.
static void TestWorstPixels(const std::string &dir) {
    std::string err, grey = "P3 4 3 255\n";
    for (int k = 0; k < 12; k++)
        grey += "100 100 100\n";
    std::string changed = grey;
    auto set = [&changed](int x, int y, const char *rgb) {
        size_t at = 11 + (size_t)(4 * y + x) * 12; // each pixel's line is 12 characters
        changed.replace(at, 11, rgb);
    };
    set(3, 0, "100 109 100"), set(1, 2, "100 100 300"), set(0, 1, "091 100 100");
    changed.replace(changed.find("300"), 3, "255"); // (200 levels, written in range)
    std::ofstream(dir + "/grey.ppm") << grey;
    std::ofstream(dir + "/changed.ppm") << changed;
    int status = RunRay(dir, "--compare grey.ppm changed.ppm --tolerance 2", &err);
    std::string out = ReadOutput(dir);
    CHECK(status == 1 && out.find("pixels over tolerance 2: 3 of 12\n"
                                  "worst pixels (x y: first image, second image):\n"
                                  "  1 2: 100 100 100, 100 100 255\n"
                                  "  3 0: 100 100 100, 100 109 100\n"
                                  "  0 1: 100 100 100, 91 100 100\n") != std::string::npos,
          "--compare lists the worst pixels, largest first, then in reading order (" + out + ")");
    CHECK(RunRay(dir, "--compare grey.ppm changed.ppm --tolerance 9", &err) == 1 &&
              ReadOutput(dir).find("  1 2: 100 100 100, 100 100 255\n") != std::string::npos &&
              ReadOutput(dir).find("  3 0") == std::string::npos,
          "--compare lists only pixels over the tolerance");
}

// Every image is read only as far as its header's size allows: /dev/zero is no image at its
// first byte (rt used to read it until memory ran out); a PNG that goes on past what an image of
// its size can hold (twice its pixels uncompressed, and 16 MiB), and a plain PPM whose samples
// lie past 16 bytes each, stop there, named; a P6 is read to its last sample and no further.
static void TestBoundedReading(const std::string &dir) {
    std::string err, padded = "P3 2 1 255\n" + std::string(100000, ' ') + "0 0 0 0 0 0\n";
    RunRay(dir, "--size 4 -o four.png", &err);
    std::ofstream(dir + "/padded.ppm") << padded;
    std::ofstream(dir + "/long.png", std::ios::binary)
        << ReadFile(dir + "/four.png") << std::string((size_t)17 << 20, '\0');
    const struct {
        const char *pipe, *file, *message;
    } bad[] = {
        {"", "/dev/zero", "/dev/zero: not a PNG or PPM image"},
        {"", "long.png",
         "long.png: goes on past 16777320 bytes, more than a PNG of 4 x 4 can hold"},
        {"", "padded.ppm", "padded.ppm: goes on past 107 bytes without its 2 x 1 pixels"},
        {"(printf 'P3 1 1 255 '; cat /dev/zero) |", "/dev/stdin",
         "/dev/stdin: the PPM ends before its 1 x 1 pixels"},
    };
    for (const auto &b : bad)
        CHECK(RunRayAfter(dir, b.pipe, "--compare four.png " + std::string(b.file), &err) == 2 &&
                  err.find(b.message) != std::string::npos,
              std::string("--compare with ") + b.file + ": exit 2, " + b.message + " (" + err +
                  ")");
    CHECK(RunRayAfter(dir, "(printf 'P6 4 4 255\\n'; cat /dev/zero) |",
                      "--compare four.png /dev/stdin --tolerance 255", &err) == 0,
          "a P6 of 4 x 4 followed by an endless file: its 48 samples read, the rest not (" + err +
              ")");
    remove((dir + "/long.png").c_str());
}

void TestCompare(const std::string &dir) {
    std::string err;
    RunRay(dir, "--size 32 -o a.png", &err);
    RunRay(dir, "--size 32 -o b.png --depth 1", &err); // mirrors turn black: very different
    CHECK(RunRay(dir, "--compare a.png a.png", &err) == 0 &&
              ReadOutput(dir).find("largest difference: 0") != std::string::npos,
          "--compare of an image with itself: exit 0, largest difference 0");
    CHECK(RunRay(dir, "--compare a.png b.png -o heat.png", &err) == 1 &&
              FileExists(dir + "/heat.png"),
          "--compare of different images: exit 1, heat map written");
    CHECK(RunRay(dir, "--compare a.png b.png --tolerance 255", &err) == 0,
          "--compare within tolerance 255: exit 0");
    CHECK(RunRay(dir, "--compare a.png nothere.png", &err) == 2, "--compare of a missing file: 2");
    CHECK(RunRay(dir, "--compare a.png b.png --tolerance 1e-400", &err) == 1 &&
              ReadOutput(dir).find("pixels over tolerance 0: ") != std::string::npos,
          "--tolerance 1e-400, too small to be anything but 0, counts as 0 (" + err + ")");
    // A 16-bit PNG without gAMA or sRGB (one pixel of 200, 100 and 50 times 257: IHDR bit depth
    // 16, colour type 2; IDAT the filter byte 0 and the six bytes c8 c8 64 64 32 32, deflated)
    // reads as the 8-bit pixel of the same colours, not as linear light re-encoded
    const unsigned char png16[] = {
        0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48, 0x44,
        0x52, 0x00, 0x00, 0x00, 0x01, 0x00, 0x00, 0x00, 0x01, 0x10, 0x02, 0x00, 0x00, 0x00, 0xc0,
        0xe7, 0x8f, 0x9d, 0x00, 0x00, 0x00, 0x0f, 0x49, 0x44, 0x41, 0x54, 0x78, 0x9c, 0x63, 0x38,
        0x71, 0x22, 0x25, 0xc5, 0xc8, 0x08, 0x00, 0x0b, 0xf1, 0x02, 0xbd, 0xe0, 0x77, 0x27, 0xff,
        0x00, 0x00, 0x00, 0x00, 0x49, 0x45, 0x4e, 0x44, 0xae, 0x42, 0x60, 0x82};
    std::ofstream(dir + "/sixteen.png", std::ios::binary).write((const char *)png16, sizeof png16);
    Image sixteen;
    std::string readError;
    bool read = ReadImage((dir + "/sixteen.png").c_str(), &sixteen, &readError);
    CHECK(read && sixteen.width == 1 && sixteen.height == 1 && sixteen.pixels[0] == 200 &&
              sixteen.pixels[1] == 100 && sixteen.pixels[2] == 50,
          "a 16-bit PNG of (200, 100, 50) x 257 reads as the 8-bit (200, 100, 50)");
    TestComparePpm(dir);
    TestWorstPixels(dir);
    TestBoundedReading(dir);
}
