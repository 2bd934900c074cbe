// bench/svg.cpp -- fitted axes and non-overlapping labels for the bench's SVG plots (svg.h).
#include "svg.h"

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>

// Pixels between the frame and the outermost data: room for a label beside an outermost marker.
static const double kInset = 20;

// The text with the characters SVG reserves escaped.
static std::string Escape(const std::string &text) {
    std::string out;
    for (char c : text)
        out += c == '<' ? "&lt;" : c == '&' ? "&amp;" : std::string(1, c);
    return out;
}

std::string Format(const char *format, ...) {
    va_list args, again;
    va_start(args, format);
    va_copy(again, args);
    int size = vsnprintf(nullptr, 0, format, args);
    va_end(args);
    std::string text(size > 0 ? size + 1 : 1, '\0');
    vsnprintf(&text[0], text.size(), format, again);
    va_end(again);
    text.resize(size > 0 ? size : 0);
    return text;
}

// Mantissas of the log grids, coarsest first: decades, half-decades (3 standing for 10^0.5),
// 1-2-5 steps, and every integer (for ticks only).
static const std::vector<double> kGrids[] = {{1}, {1, 3}, {1, 2, 5}, {1, 2, 3, 4, 5, 6, 7, 8, 9}};

// The values of `grid` times powers of ten in [lo, hi].
static std::vector<double> GridValues(const std::vector<double> &grid, double lo, double hi) {
    std::vector<double> out;
    for (int e = (int)std::floor(std::log10(lo)) - 1; e <= (int)std::ceil(std::log10(hi)); e++)
        for (double m : grid) {
            double v = m * std::pow(10.0, e);
            if (v >= lo * (1 - 1e-9) && v <= hi * (1 + 1e-9))
                out.push_back(v);
        }
    return out;
}

// The grid value nearest v at or below it (or, with `up`, at or above it).
static double Snap(double v, const std::vector<double> &grid, bool up) {
    std::vector<double> near = GridValues(grid, v / 10.5, v * 10.5);
    double best = up ? near.back() : near.front();
    for (double g : near)
        if (up ? (g >= v * (1 - 1e-9) && g < best) : (g <= v * (1 + 1e-9) && g > best))
            best = g;
    return best;
}

// A round step (1, 2 or 5 times a power of ten) that cuts `span` into about `parts`.
static double NiceStep(double span, int parts) {
    double raw = span / parts, unit = std::pow(10.0, std::floor(std::log10(raw)));
    for (double m : {1.0, 2.0, 5.0})
        if (m * unit >= raw * (1 - 1e-9))
            return m * unit;
    return 10 * unit;
}

static std::vector<double> LinearTicks(double lo, double hi) {
    double step = NiceStep(hi - lo, 5);
    std::vector<double> out;
    for (double v = std::ceil(lo / step - 1e-9) * step; v <= hi + 1e-9 * step; v += step)
        out.push_back(std::fabs(v) < 1e-12 * step ? 0 : v);
    return out;
}

// Snaps the ends to the coarsest grid that widens the span by at most 15%; ticks on the
// coarsest grid that gives 3 to 9 of them (every other decade over a wide span).
static void FitLog(double lo, double hi, SvgAxis *a) {
    if (!(hi > 0)) // nothing to show on a log scale: 1 to 10
        lo = 1, hi = 10;
    if (!(lo > 0))
        lo = hi / 10;
    if (std::log10(hi / lo) < 0.2) {
        double centre = std::sqrt(lo * hi), half = std::pow(10.0, 0.1);
        lo = centre / half, hi = centre * half;
    }
    double span = std::log10(hi / lo);
    a->lo = lo, a->hi = hi;
    for (int g = 0; g < 3; g++) {
        double l = Snap(lo, kGrids[g], false), h = Snap(hi, kGrids[g], true);
        if (std::log10(h / l) <= 1.15 * span) {
            a->lo = l, a->hi = h;
            break;
        }
    }
    for (const std::vector<double> &grid : kGrids) {
        std::vector<double> ticks = GridValues(grid, a->lo, a->hi);
        size_t every = (ticks.size() + 7) / 8;
        for (size_t k = 0; k < ticks.size() && ticks.size() >= 3; k += every)
            a->ticks.push_back(ticks[k]);
        if (!a->ticks.empty())
            return;
    }
    a->ticks = LinearTicks(a->lo, a->hi);
}

SvgAxis FitAxis(double lo, double hi, bool log, double from, double to) {
    double sign = to > from ? 1 : -1;
    SvgAxis a = {lo, hi, log, from + sign * kInset, to - sign * kInset, {}};
    if (log) {
        FitLog(lo, hi, &a);
        return a;
    }
    if (hi - lo <= 1e-12 * std::max(std::fabs(lo), std::fabs(hi)))
        lo -= std::max(std::fabs(lo) * 0.1, 1.0), hi += std::max(std::fabs(hi) * 0.1, 1.0);
    double step = NiceStep(hi - lo, 20); // ends on round numbers, about 5% apart
    a.lo = std::floor(lo / step + 1e-9) * step, a.hi = std::ceil(hi / step - 1e-9) * step;
    a.ticks = LinearTicks(a.lo, a.hi);
    return a;
}

SvgBox FrameBox(const SvgAxis &x, const SvgAxis &y) {
    return {std::min(x.p0, x.p1) - kInset, std::min(y.p0, y.p1) - kInset,
            std::max(x.p0, x.p1) + kInset, std::max(y.p0, y.p1) + kInset};
}

double AxisPixel(const SvgAxis &a, double v) {
    double t = a.log ? std::log(v / a.lo) / std::log(a.hi / a.lo) : (v - a.lo) / (a.hi - a.lo);
    return a.p0 + t * (a.p1 - a.p0);
}

// 3e-4, 0.01, 250, 1e4: short tick labels.
static std::string TickText(double v) {
    double size = std::fabs(v);
    if (size > 0 && (size >= 1e4 || size < 1e-3)) {
        int e = (int)std::floor(std::log10(size) + 1e-9);
        return Format("%ge%d", std::round(v / std::pow(10.0, e) * 100) / 100, e);
    }
    return Format("%g", v);
}

std::string SvgFrame(const SvgAxis &x, const SvgAxis &y, const char *xTitle, const char *yTitle) {
    SvgBox frame = FrameBox(x, y);
    double left = frame.x0, right = frame.x1, top = frame.y0, bottom = frame.y1;
    std::string out = Format("<rect x='%.1f' y='%.1f' width='%.1f' height='%.1f' fill='none' "
                             "stroke='#888'/>\n",
                             left, top, right - left, bottom - top);
    for (double v : x.ticks)
        out += Format("<line x1='%.1f' y1='%.1f' x2='%.1f' y2='%.1f' stroke='#eee'/>\n<text "
                      "x='%.1f' y='%.1f' text-anchor='middle'>%s</text>\n",
                      AxisPixel(x, v), top + 1, AxisPixel(x, v), bottom - 1, AxisPixel(x, v),
                      bottom + 16, TickText(v).c_str());
    size_t widest = 0;
    for (double v : y.ticks) {
        widest = std::max(widest, TickText(v).size());
        out += Format("<line x1='%.1f' y1='%.1f' x2='%.1f' y2='%.1f' stroke='#eee'/>\n<text "
                      "x='%.1f' y='%.1f' text-anchor='end'>%s</text>\n",
                      left + 1, AxisPixel(y, v), right - 1, AxisPixel(y, v), left - 5,
                      AxisPixel(y, v) + 4, TickText(v).c_str());
    }
    double titleX = left - 5 - 7.0 * widest - 10, middle = (top + bottom) / 2;
    out += Format("<text x='%.1f' y='%.1f' text-anchor='middle'>%s</text>\n<text x='%.1f' "
                  "y='%.1f' transform='rotate(-90 %.1f %.1f)' text-anchor='middle'>%s</text>\n",
                  (left + right) / 2, bottom + 36, xTitle, titleX, middle, titleX, middle, yTitle);
    return out;
}

void AddMarker(SvgLabels *labels, double x, double y, double r) {
    labels->markers.push_back({x, y, r});
}

void AddLine(SvgLabels *labels, double x0, double y0, double x1, double y1, bool hard) {
    (hard ? labels->bars : labels->lines).push_back({x0, y0, x1, y1});
}

// Whether two labels' boxes overlap or come closer than 3 pixels (as one label would read).
static bool Overlap(const SvgBox &a, const SvgBox &b) {
    const double gap = 3;
    return a.x0 < b.x1 + gap && b.x0 < a.x1 + gap && a.y0 < b.y1 + gap && b.y0 < a.y1 + gap;
}

static bool HitsCircle(const SvgBox &b, const SvgCircle &c) {
    double dx = std::max({b.x0 - c.x, 0.0, c.x - b.x1}),
           dy = std::max({b.y0 - c.y, 0.0, c.y - b.y1});
    return dx * dx + dy * dy < (c.r + 1) * (c.r + 1);
}

// Whether the segment crosses the box (Liang-Barsky clipping).
static bool HitsSegment(const SvgBox &b, const SvgSegment &s) {
    double dx = s.x1 - s.x0, dy = s.y1 - s.y0, t0 = 0, t1 = 1;
    double p[4] = {-dx, dx, -dy, dy}, q[4] = {s.x0 - b.x0, b.x1 - s.x0, s.y0 - b.y0, b.y1 - s.y0};
    for (int k = 0; k < 4; k++) {
        if (p[k] == 0) {
            if (q[k] < 0)
                return false;
        } else if (p[k] < 0) {
            t0 = std::max(t0, q[k] / p[k]);
        } else {
            t1 = std::min(t1, q[k] / p[k]);
        }
    }
    return t0 <= t1;
}

// The line from a marker at (x, y) to the nearest point of a label's box.
static SvgSegment Leader(double x, double y, const SvgBox &b) {
    return {x, y, std::clamp(x, b.x0, b.x1), std::clamp(y, b.y0, b.y1)};
}

// Whether a label may take the box: inside the area, clear of labels, markers and bars, and
// (when `strict`) of the plotted lines; with `leader`, the line to it from the marker at (x, y)
// crosses no label either.
static bool Free(const SvgLabels &l, const SvgBox &b, bool strict, bool leader, double x,
                 double y) {
    if (b.x0 < l.area.x0 || b.y0 < l.area.y0 || b.x1 > l.area.x1 || b.y1 > l.area.y1)
        return false;
    for (const SvgBox &p : l.placed)
        if (Overlap(b, p) || (leader && HitsSegment(p, Leader(x, y, b))))
            return false;
    for (const SvgCircle &c : l.markers)
        if (HitsCircle(b, c))
            return false;
    for (const SvgSegment &s : l.bars)
        if (HitsSegment(b, s))
            return false;
    for (const SvgSegment &s : l.lines)
        if (strict && HitsSegment(b, s))
            return false;
    return true;
}

// How many other markers lie within 16 pixels of the box: a box there may take the only room
// their own labels have.
static int Crowding(const SvgLabels &l, const SvgBox &b, double x, double y) {
    int near = 0;
    for (const SvgCircle &c : l.markers)
        near += (c.x != x || c.y != y) && HitsCircle(b, {c.x, c.y, c.r + 16});
    return near;
}

// A free box of width w and height h beside the marker, among: right, left, above and below
// (centred, then starting or ending at the marker), then the diagonals; first clear of lines
// too, then of labels, markers and bars only. Of the free ones, the one nearest the fewest
// other markers, the first in that order on a tie. False if none is free.
static bool FreeBox(const SvgLabels &l, double x, double y, double r, double w, double h,
                    bool leader, SvgBox *out) {
    const double g = 3, d = r * 0.7, up = y - r - g - h, down = y + r + g;
    const double corners[12][2] = {{x + r + g, y - h / 2},
                                   {x - r - g - w, y - h / 2},
                                   {x - w / 2, up},
                                   {x - w / 2, down},
                                   {x - r, up},
                                   {x + r - w, up},
                                   {x - r, down},
                                   {x + r - w, down},
                                   {x + d, y - d - h},
                                   {x + d, y + d},
                                   {x - d - w, y - d - h},
                                   {x - d - w, y + d}};
    for (bool strict : {true, false}) {
        int best = 1 << 30;
        for (const auto &c : corners) {
            SvgBox b = {c[0], c[1], c[0] + w, c[1] + h};
            int crowding = Free(l, b, strict, leader, x, y) ? Crowding(l, b, x, y) : 1 << 30;
            if (crowding < best)
                best = crowding, *out = b;
        }
        if (best < 1 << 30)
            return true;
    }
    return false;
}

// Of the boxes of width w and height h on a 4-pixel grid over the whole area, the free one
// nearest (x, y), lines allowed; false if none.
static bool NearestFreeBox(const SvgLabels &l, double x, double y, double w, double h,
                           SvgBox *out) {
    double best = 1e30;
    for (double x0 = l.area.x0; x0 + w <= l.area.x1; x0 += 4)
        for (double y0 = l.area.y0; y0 + h <= l.area.y1; y0 += 4) {
            SvgBox b = {x0, y0, x0 + w, y0 + h};
            SvgSegment s = Leader(x, y, b);
            double d = std::hypot(s.x1 - x, s.y1 - y);
            if (d < best && Free(l, b, false, false, x, y))
                best = d, *out = b;
        }
    return best < 1e30;
}

static std::string TextAt(const SvgBox &b, const std::string &text, const char *fill, int size) {
    return Format("<text x='%.1f' y='%.1f' font-size='%d' fill='%s'>%s</text>\n", b.x0,
                  b.y1 - 0.2 * size, size, fill, Escape(text).c_str());
}

std::string PlaceLabel(SvgLabels *l, double x, double y, double r, const std::string &text,
                       const char *fill, int fontSize) {
    double charWidth = 7.0 * fontSize / 12;
    SvgBox box;
    if (FreeBox(*l, x, y, r, charWidth * text.size(), fontSize, false, &box)) {
        l->placed.push_back(box);
        return TextAt(box, text, fill, fontSize);
    }
    std::string tag = text; // a label of a character or two stays itself, only placed away
    if (text.size() > 2) {  // A to Z, then AA, AB...: letters, apart from the numbers plotted
        size_t k = l->legend.size();
        tag = k < 26 ? std::string(1, char('A' + k))
                     : std::string(1, char('A' + k / 26 - 1)) + char('A' + k % 26);
        l->legend.push_back(tag + "  " + text);
        l->legendFill.push_back(fill);
    }
    double w = charWidth * tag.size(), away = 0;
    bool found = FreeBox(*l, x, y, r, w, fontSize, false, &box);
    for (int pass = 0; pass < 10 && !found; pass++) { // the tag may stand away, a line leading
        away = 6 * (pass % 5 + 1);                    // to it: first a line crossing no label
        found = FreeBox(*l, x, y, r + away, w, fontSize, pass < 5, &box);
    }
    if (!found)
        found = NearestFreeBox(*l, x, y, w, fontSize, &box), away = found ? 1 : 0;
    if (!found) // nowhere free: above right, over whatever is there
        box = {x + r + 1, y - r - fontSize, x + r + 1 + w, y - r};
    std::string leader;
    if (found && away > 0) {
        SvgSegment s = Leader(x, y, box);
        leader = Format("<line x1='%.1f' y1='%.1f' x2='%.1f' y2='%.1f' stroke='%s' "
                        "stroke-width='0.7'/>\n",
                        s.x0, s.y0, s.x1, s.y1, fill);
    }
    l->placed.push_back(box);
    return leader + TextAt(box, tag, fill, fontSize);
}

std::string PlaceLabels(SvgLabels *l, const std::vector<SvgMark> &marks) {
    std::vector<int> crowd(marks.size(), 0), order;
    for (size_t k = 0; k < marks.size(); k++) {
        order.push_back((int)k);
        for (const SvgCircle &c : l->markers)
            crowd[k] += std::hypot(c.x - marks[k].x, c.y - marks[k].y) < 50;
    }
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return crowd[a] > crowd[b]; });
    std::string out;
    for (int k : order) {
        const SvgMark &m = marks[k];
        out += PlaceLabel(l, m.x, m.y, m.r, m.text, m.fill, m.fontSize);
    }
    return out;
}

std::string SvgLegend(const SvgLabels &l, double x, double y, double step) {
    std::string out;
    for (size_t k = 0; k < l.legend.size(); k++)
        out += Format("<text x='%.1f' y='%.1f' fill='%s'>%s</text>\n", x, y + step * k,
                      l.legendFill[k].c_str(), Escape(l.legend[k]).c_str());
    return out;
}

Spread SpreadOf(std::vector<double> times) {
    if (times.empty())
        return {0, 0, 0};
    std::sort(times.begin(), times.end());
    size_t n = times.size();
    double median = n % 2 ? times[n / 2] : (times[n / 2 - 1] + times[n / 2]) / 2;
    return {median, times.front(), times.back()};
}

bool WithinNoise(const Spread &a, const Spread &b) { return a.min <= b.max && b.min <= a.max; }

std::string SpreadText(const Spread &s, const char *format) {
    std::string f = std::string(format) + " (" + format + "-" + format + ")";
    char text[128];
    snprintf(text, sizeof text, f.c_str(), s.median, s.min, s.max);
    return text;
}
