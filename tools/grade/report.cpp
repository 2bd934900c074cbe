// tools/grade/report.cpp -- what the grades are written as: a line a scene for the terminal, a
// page a student can read, Gradescope's results.json, and a class's marks.csv.
#include "grade.h"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <png.h>
#include <unistd.h>

static long Passed(const std::vector<SceneResult> &results) {
    long n = 0;
    for (const SceneResult &r : results)
        n += r.verdict == VERDICT_PASS;
    return n;
}

std::string TextReport(const std::vector<SceneResult> &results) {
    std::string text;
    for (const SceneResult &r : results)
        text += r.verdict == VERDICT_PASS
                    ? "pass  " + r.scene + (r.text.empty() ? "" : " (" + r.text + ")") + "\n"
                    : "FAIL  " + r.scene + ": " + r.text + "\n";
    return text + std::to_string(Passed(results)) + " of " + std::to_string(results.size()) +
           " scenes pass\n";
}

// ---- the page ---------------------------------------------------------------------------

static std::string Escape(const std::string &s) {
    std::string out;
    for (char c : s)
        out += c == '<' ? "&lt;" : c == '>' ? "&gt;" : c == '&' ? "&amp;" : c == '"' ? "&quot;" : std::string(1, c);
    return out;
}

// An image as a data: URI (a PNG, base64), or "" if it cannot be encoded.
static std::string DataUri(const Image *image) {
    if (image->width <= 0 || image->height <= 0)
        return "";
    png_image png;
    memset(&png, 0, sizeof png);
    png.version = PNG_IMAGE_VERSION, png.width = image->width, png.height = image->height;
    png.format = PNG_FORMAT_RGB;
    png_alloc_size_t size = 0;
    if (!png_image_write_to_memory(&png, nullptr, &size, 0, image->pixels.data(), 0, nullptr))
        return "";
    std::vector<unsigned char> bytes(size);
    if (!png_image_write_to_memory(&png, bytes.data(), &size, 0, image->pixels.data(), 0, nullptr))
        return "";
    static const char kDigits[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out = "data:image/png;base64,";
    for (size_t i = 0; i < size; i += 3) { // 3 bytes in 4 digits, `=` where bytes run out
        size_t n = std::min<size_t>(3, size - i);
        unsigned v = bytes[i] << 16 | (n > 1 ? bytes[i + 1] << 8 : 0) | (n > 2 ? bytes[i + 2] : 0);
        for (size_t k = 0; k < 4; k++)
            out += k <= n ? kDigits[(v >> (18 - 6 * k)) & 63] : '=';
    }
    return out;
}

static std::string Picture(const Image *image, const char *caption) {
    std::string uri = DataUri(image);
    if (uri.empty())
        return "";
    return "<figure><img src=\"" + uri + "\" width=\"" + std::to_string(4 * image->width) +
           "\" style=\"image-rendering: pixelated\"><figcaption>" + caption + "</figcaption></figure>";
}

std::string HtmlReport(const std::string &title, const std::vector<SceneResult> &results,
                       const ReferenceSet *set) {
    std::string page = "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>" + Escape(title) +
                       "</title><style>body{font-family:sans-serif;max-width:60em;margin:2em auto}"
                       "figure{display:inline-block;margin:0 1em 1em 0}.pass{color:#070}"
                       ".fail{color:#a00}</style></head><body>\n<h1>" + Escape(title) + "</h1>\n<p>" +
                       std::to_string(Passed(results)) + " of " + std::to_string(results.size()) +
                       " scenes pass.</p>\n";
    for (const SceneResult &r : results) {
        bool pass = r.verdict == VERDICT_PASS;
        page += "<h2 class=\"" + std::string(pass ? "pass" : "fail") + "\">" + Escape(r.scene) + ": " +
                VerdictWord(r.verdict) + "</h2>\n";
        if (!r.text.empty())
            page += "<p>" + Escape(r.text) + "</p>\n";
        if (pass)
            continue;
        for (const SetScene &s : set->scenes)
            if (s.name == r.scene)
                page += Picture(&s.reference, "rt's image");
        page += Picture(&r.image, "yours") + Picture(&r.heatmap, "where they differ") + "\n";
    }
    return page + "</body></html>\n";
}

// ---- Gradescope and the class's marks ---------------------------------------------------

static std::string JsonString(const std::string &s) {
    std::string out = "\"";
    for (unsigned char c : s) {
        if (c == '"' || c == '\\')
            out += '\\', out += (char)c;
        else if (c == '\n')
            out += "\\n";
        else if (c < 0x20) {
            char hex[8];
            snprintf(hex, sizeof hex, "\\u%04x", c);
            out += hex;
        } else
            out += (char)c;
    }
    return out + "\"";
}

std::string GradescopeJson(const std::vector<SceneResult> &results, const std::string &output) {
    std::string json = "{\n  \"output\": " + JsonString(output) + ",\n  \"tests\": [";
    for (size_t k = 0; k < results.size(); k++) {
        const SceneResult &r = results[k];
        bool pass = r.verdict == VERDICT_PASS;
        json += std::string(k ? "," : "") + "\n    {\"name\": " + JsonString(r.scene) +
                ", \"score\": " + (pass ? "1" : "0") + ", \"max_score\": 1, \"status\": " +
                (pass ? "\"passed\"" : "\"failed\"") + ", \"output\": " +
                JsonString(pass ? "pass" : r.text) + ", \"visibility\": \"visible\"}";
    }
    return json + "\n  ]\n}\n";
}

static std::string CsvField(const std::string &s) {
    if (s.find_first_of(",\"\n") == std::string::npos)
        return s;
    std::string out = "\"";
    for (char c : s)
        out += c == '"' ? std::string("\"\"") : std::string(1, c);
    return out + "\"";
}

std::string CsvHeader(const ReferenceSet *set) {
    std::string row = "student";
    for (const SetScene &s : set->scenes)
        row += "," + s.name;
    return row + ",passed,total\n";
}

std::string CsvRow(const std::string &student, const std::vector<SceneResult> &results) {
    std::string row = CsvField(student);
    for (const SceneResult &r : results)
        row += std::string(",") + VerdictWord(r.verdict);
    return row + "," + std::to_string(Passed(results)) + "," + std::to_string(results.size()) + "\n";
}

bool WriteTextFile(const std::string &path, const std::string &text, std::string *error) {
    std::string temporary = path + ".tmp" + std::to_string((long)getpid());
    FILE *file = fopen(temporary.c_str(), "wb");
    bool written = file && fwrite(text.data(), 1, text.size(), file) == text.size();
    if (file && fclose(file) != 0)
        written = false;
    if (written && rename(temporary.c_str(), path.c_str()) == 0)
        return true;
    *error = path + ": " + strerror(errno);
    unlink(temporary.c_str());
    return false;
}
