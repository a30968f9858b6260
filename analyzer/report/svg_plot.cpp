#include "svg_plot.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "sinks/xml_escape.h"

namespace busdecode {

namespace {

std::string num(double v) {
    return fmt::format("{:.1f}", v);
}

double niceStep(double span, int target) {
    const double raw = span / std::max(target, 1);
    const double mag = std::pow(10.0, std::floor(std::log10(raw)));
    for (double m : {1.0, 2.0, 5.0})
        if (raw <= m * mag) return m * mag;
    return 10 * mag;
}

// Tick labels are 11 px monospace (html_report.cpp's style): 0.6 em a character.
constexpr double kCharWidth = 6.6;

// The widest y tick label's width, the values times `scale`.
double widestTickLabel(const PlotAxis& axis, double scale) {
    const auto ticks = niceTicks(axis.lo, axis.hi, 5);
    const double step = ticks.size() > 1 ? ticks[1] - ticks[0] : 1;
    std::size_t chars = 0;
    for (double v : ticks)
        chars = std::max(chars, tickText(v * scale, step * scale).size());
    return double(chars) * kCharWidth;
}

}  // namespace

std::vector<double> niceTicks(double lo, double hi, int target) {
    if (!(hi > lo) || !std::isfinite(lo) || !std::isfinite(hi)) return {lo};
    const double step = niceStep(hi - lo, target);
    std::vector<double> out;
    for (double v = std::ceil(lo / step - 1e-9) * step; v <= hi + step * 1e-9; v += step)
        out.push_back(std::fabs(v) < step * 1e-9 ? 0.0 : v);
    return out;
}

std::string tickText(double v, double step) {
    int decimals = 0;
    if (step > 0 && step < 1) decimals = int(std::ceil(-std::log10(step) - 1e-9));
    // Whole counts stay whole (67108800, not 6.71e+07: neighbours must differ).
    if (std::fabs(v) >= 1e15) return fmt::format("{:.6g}", v);
    return fmt::format("{:.{}f}", v, std::min(decimals, 9));
}

TimeUnit timeUnitFor(double span_ns) {
    const double a = std::fabs(span_ns);
    if (a >= 2e9) return {"s", 1e9};
    if (a >= 2e6) return {"ms", 1e6};
    if (a >= 2e3) return {"us", 1e3};
    return {"ns", 1};
}

SvgPlot::SvgPlot(std::string css_class, double width, double height, std::string title, PlotAxis x,
                 PlotAxis y)
    : css_class_(std::move(css_class)),
      title_(std::move(title)),
      xa_(std::move(x)),
      ya_(std::move(y)),
      W_(width),
      H_(height) {
    for (PlotAxis* a : {&xa_, &ya_})
        if (!(a->hi > a->lo)) {
            a->lo -= 0.5;
            a->hi += 0.5;
        }
    // Room for the y labels between the rotated axis title (to x = 24) and the frame.
    L_ = std::max(L_, 29 + widestTickLabel(ya_, 1));
}

double SvgPlot::x(double v) const {
    return L_ + (v - xa_.lo) / (xa_.hi - xa_.lo) * (W_ - L_ - R_);
}

double SvgPlot::y(double v) const {
    return T_ + (ya_.hi - v) / (ya_.hi - ya_.lo) * (H_ - T_ - B_);
}

void SvgPlot::secondYAxis(double scale, std::string title) {
    second_scale_ = scale;
    second_title_ = std::move(title);
    // Room for its labels between the frame and its rotated title (from W - 22).
    R_ = std::max(70.0, 27 + widestTickLabel(ya_, scale));
}

std::string SvgPlot::svg() const {
    std::string s = fmt::format(
        R"(<svg class="{0}" xmlns="http://www.w3.org/2000/svg" width="{1}" height="{2}" viewBox="0 0 {1} {2}">)",
        css_class_, W_, H_);
    s += fmt::format(R"(<text class="plot-title" x="{}" y="16">{}</text>)", L_, xmlEscape(title_));
    // Grid and ticks first, so the data is drawn over them.
    const auto yt = y_ticks_ ? niceTicks(ya_.lo, ya_.hi, 5) : std::vector<double>{};
    const double ystep = yt.size() > 1 ? yt[1] - yt[0] : 1;
    for (double v : yt) {
        s += fmt::format(
            R"(<line class="grid" x1="{0}" y1="{2}" x2="{1}" y2="{2}" stroke="#e4e4e4"/>)", L_,
            num(right()), num(y(v)));
        s += fmt::format(R"(<text class="tick y" x="{}" y="{}" text-anchor="end">{}</text>)",
                         num(L_ - 5), num(y(v) + 4), tickText(v, ystep));
        if (second_scale_ > 0)
            s += fmt::format(R"(<text class="tick y2" x="{}" y="{}">{}</text>)", num(right() + 5),
                             num(y(v) + 4), tickText(v * second_scale_, ystep * second_scale_));
    }
    const auto xt = x_ticks_.empty() ? niceTicks(xa_.lo, xa_.hi, 6) : x_ticks_;
    const double xstep = xt.size() > 1 ? xt[1] - xt[0] : 1;
    for (double v : xt) {
        if (v < xa_.lo || v > xa_.hi) continue;
        s += fmt::format(
            R"(<line class="grid" x1="{0}" y1="{1}" x2="{0}" y2="{2}" stroke="#e4e4e4"/>)",
            num(x(v)), T_, num(bottom()));
        s += fmt::format(R"(<text class="tick x" x="{}" y="{}" text-anchor="middle">{}</text>)",
                         num(x(v)), num(bottom() + 15), tickText(v, xstep));
    }
    s += fmt::format(R"(<rect x="{}" y="{}" width="{}" height="{}" fill="none" stroke="#888"/>)",
                     L_, T_, num(right() - L_), num(bottom() - T_));
    s += fmt::format(R"(<text class="axis-title x" x="{}" y="{}" text-anchor="middle">{}</text>)",
                     num((L_ + right()) / 2), num(H_ - 6), xmlEscape(xa_.title));
    s += fmt::format(
        R"svg(<text class="axis-title y" x="{0}" y="{1}" text-anchor="middle" transform="rotate(-90 {0} {1})">{2}</text>)svg",
        14, num((T_ + bottom()) / 2), xmlEscape(ya_.title));
    if (second_scale_ > 0)
        s += fmt::format(
            R"svg(<text class="axis-title y2" x="{0}" y="{1}" text-anchor="middle" transform="rotate(90 {0} {1})">{2}</text>)svg",
            num(W_ - 12), num((T_ + bottom()) / 2), xmlEscape(second_title_));
    return s + body_ + "</svg>\n";
}

}  // namespace busdecode
