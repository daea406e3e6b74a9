// LDR-FLIP (Andersson et al., HPG 2020) and HDR-FLIP (Andersson et al., EG 2021 short paper),
// written from the papers. Section and equation numbers below are those of the HPG 2020 paper
// unless marked HDR-FLIP. Filters are separable and clamp at the image border.
#include "metrics/flip.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>

#include "core/error.h"
#include "metrics/color_difference.h"
#include "metrics/image_metrics.h"

namespace iris {

namespace {
constexpr double kPi = 3.14159265358979323846;
}

namespace flip {

double pixelsPerDegree(double distanceM, double monitorWidthM, double resolutionX) {
    return distanceM * (resolutionX / monitorWidthM) * (kPi / 180.0);
}

void huntLab(double r, double g, double b, double out[3]) {
    const Lab lab = linearRec709ToLab(r, g, b);
    // §4.1.2: the Hunt effect, chroma grows with luminance: a_h = 0.01 L a, b_h = 0.01 L b.
    out[0] = lab.L;
    out[1] = 0.01 * lab.L * lab.a;
    out[2] = 0.01 * lab.L * lab.b;
}

double hyab(const double x[3], const double y[3]) {
    // §4.1.3, eq. 8: city-block distance in lightness plus Euclidean distance in a, b.
    return std::abs(x[0] - y[0]) + std::hypot(x[1] - y[1], x[2] - y[2]);
}

double colorMax() {
    static const double cmax = [] {
        double green[3], blue[3];
        huntLab(0, 1, 0, green);
        huntLab(0, 0, 1, blue);
        return std::pow(hyab(green, blue), kQc);
    }();
    return cmax;
}

double remapColorError(double powered) {
    // §4.1.3: [0, p_c c_max) → [0, p_t) and [p_c c_max, c_max] → [p_t, 1], both linear.
    const double cmax = colorMax(), knee = kPc * cmax;
    if (powered < knee) return powered * (kPt / knee);
    return kPt + (powered - knee) / (cmax - knee) * (1.0 - kPt);
}

int csfRadius(double ppd) {
    double bMax = 0;
    for (const CsfChannel& c : kCsf) bMax = std::max({bMax, c.b1, c.b2});
    // §4.1.1: the spatial Gaussian e^{−π² x² / b} has σ = sqrt(b / (2π²)) degrees; 3σ in pixels.
    return int(std::ceil(3.0 * std::sqrt(bMax / (2.0 * kPi * kPi)) * ppd));
}

std::vector<double> csfGaussian(double b, double ppd) {
    const int r = csfRadius(ppd);
    std::vector<double> k(size_t(2 * r + 1));
    for (int i = -r; i <= r; ++i) {
        const double x = double(i) / ppd;  // degrees
        k[size_t(i + r)] = std::exp(-kPi * kPi * x * x / b);
    }
    return k;
}

namespace {

/// Scale the positive weights to sum 1 and the negative weights to sum −1 (§4.2.1).
void balanceSigns(std::vector<double>& k) {
    double pos = 0, neg = 0;
    for (double v : k) (v > 0 ? pos : neg) += v;
    for (double& v : k) v = v > 0 ? v / pos : (v < 0 ? v / -neg : 0.0);
}

}  // namespace

FeatureFilters featureFilters(double ppd) {
    const double sigma = 0.5 * kW * ppd;
    const int r = int(std::ceil(3.0 * sigma));
    FeatureFilters f;
    double sum = 0;
    for (int i = -r; i <= r; ++i) {
        const double x = double(i), g = std::exp(-x * x / (2.0 * sigma * sigma));
        f.gauss.push_back(g);
        f.first.push_back(-x * g);
        f.second.push_back((x * x / (sigma * sigma) - 1.0) * g);
        sum += g;
    }
    for (double& g : f.gauss) g /= sum;
    balanceSigns(f.first);
    balanceSigns(f.second);
    return f;
}

namespace {
// Narkowicz's ACES fit in x with the 0.6 pre-exposure folded in: y = (k0 x² + k1 x + k2) / (k3 x² + k4 x + k5).
constexpr double kAces[6] = {0.6 * 0.6 * 2.51, 0.6 * 0.03, 0.0, 0.6 * 0.6 * 2.43, 0.6 * 0.59, 0.14};
}  // namespace

double toneMapAces(double x) {
    const double y = (kAces[0] * x * x + kAces[1] * x + kAces[2]) / (kAces[3] * x * x + kAces[4] * x + kAces[5]);
    return std::clamp(y, 0.0, 1.0);
}

double inverseToneMapAces(double t) {
    // HDR-FLIP §2: y(x) = t ⇔ (t k3 − k0) x² + (t k4 − k1) x + (t k5 − k2) = 0; the larger root is
    // the non-negative one on the increasing branch.
    const double a = t * kAces[3] - kAces[0], b = t * kAces[4] - kAces[1], c = t * kAces[5] - kAces[2];
    const double disc = std::sqrt(std::max(0.0, b * b - 4.0 * a * c));
    return std::max((-b + disc) / (2.0 * a), (-b - disc) / (2.0 * a));
}

}  // namespace flip

namespace {

using Plane = std::vector<float>;

/// The colour channels of an image as interleaved RGB plus a validity mask (finite values).
struct Rgb {
    int w = 0, h = 0;
    std::vector<float> v;          // 3 per pixel
    std::vector<uint8_t> valid;    // 1 per pixel
};

Rgb colourOf(const Image& img, const std::vector<int>& ch) {
    Rgb out{img.width, img.height, std::vector<float>(img.pixelCount() * 3), std::vector<uint8_t>(img.pixelCount(), 1)};
    for (size_t p = 0; p < img.pixelCount(); ++p)
        for (int k = 0; k < 3; ++k) {
            const float x = img.pixels[p * size_t(img.channels) + size_t(ch[ch.size() == 1 ? 0 : size_t(k)])];
            if (!std::isfinite(x)) out.valid[p] = 0;
            out.v[3 * p + size_t(k)] = std::isfinite(x) ? x : 0.0f;
        }
    return out;
}

/// out(x, y) = Σ_j ky[j] Σ_i kx[i] in(x + i − rx, y + j − ry), coordinates clamped to the image.
Plane convolve(const Plane& in, int w, int h, const std::vector<double>& kx, const std::vector<double>& ky) {
    const int rx = int(kx.size() / 2), ry = int(ky.size() / 2);
    Plane tmp(in.size()), out(in.size());
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            double s = 0;
            for (int i = 0; i < int(kx.size()); ++i) s += kx[size_t(i)] * in[size_t(y) * size_t(w) + size_t(std::clamp(x + i - rx, 0, w - 1))];
            tmp[size_t(y) * size_t(w) + size_t(x)] = float(s);
        }
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            double s = 0;
            for (int j = 0; j < int(ky.size()); ++j) s += ky[size_t(j)] * tmp[size_t(std::clamp(y + j - ry, 0, h - 1)) * size_t(w) + size_t(x)];
            out[size_t(y) * size_t(w) + size_t(x)] = float(s);
        }
    return out;
}

/// YyCxCz (§4.1.1; the linearised CIELAB of Flohr, Kolpatzik et al.): Yy = 116 Y/Yn − 16,
/// Cx = 500 (X/Xn − Y/Yn), Cz = 200 (Y/Yn − Z/Zn), white = RGB (1,1,1).
std::array<Plane, 3> toYCxCz(const Rgb& img) {
    double white[3];
    rec709WhiteXYZ(white);
    std::array<Plane, 3> out;
    for (Plane& p : out) p.resize(img.valid.size());
    for (size_t p = 0; p < img.valid.size(); ++p) {
        double xyz[3];
        linearRec709ToXYZ(img.v[3 * p], img.v[3 * p + 1], img.v[3 * p + 2], xyz);
        const double x = xyz[0] / white[0], y = xyz[1] / white[1], z = xyz[2] / white[2];
        out[0][p] = float(116.0 * y - 16.0);
        out[1][p] = float(500.0 * (x - y));
        out[2][p] = float(200.0 * (y - z));
    }
    return out;
}

/// The inverse of toYCxCz for one pixel, then linear RGB clamped to [0,1] (§4.1.1).
void fromYCxCz(double yy, double cx, double cz, double rgb[3]) {
    double white[3];
    rec709WhiteXYZ(white);
    const double y = (yy + 16.0) / 116.0;
    const double xyz[3] = {white[0] * (cx / 500.0 + y), white[1] * y, white[2] * (y - cz / 200.0)};
    xyzToLinearRec709(xyz, rgb);
    for (int k = 0; k < 3; ++k) rgb[k] = std::clamp(rgb[k], 0.0, 1.0);
}

/// Channel k filtered by its contrast sensitivity: the 2-D kernel Σ_i a_i sqrt(π/b_i)
/// e^{−π²(x²+y²)/b_i} (§4.1.1, eq. 3 in 2-D) normalised to sum 1, as a mix of separable Gaussians.
Plane csfFilter(const Plane& in, int w, int h, int k, double ppd) {
    const flip::CsfChannel& c = flip::kCsf[k];
    const double terms[2][2] = {{c.a1, c.b1}, {c.a2, c.b2}};
    Plane out(in.size(), 0.0f);
    double total = 0;
    std::vector<std::pair<double, Plane>> parts;
    for (const auto& t : terms) {
        if (t[0] == 0.0) continue;
        std::vector<double> g = flip::csfGaussian(t[1], ppd);
        double s = 0;
        for (double v : g) s += v;
        for (double& v : g) v /= s;
        const double weight = t[0] * std::sqrt(kPi / t[1]) * s * s;  // the term's kernel sum
        parts.emplace_back(weight, convolve(in, w, h, g, g));
        total += weight;
    }
    for (const auto& [weight, p] : parts)
        for (size_t i = 0; i < out.size(); ++i) out[i] += float(weight / total) * p[i];
    return out;
}

/// Edge and point feature magnitudes of the normalised achromatic channel (§4.2.1).
struct Features {
    Plane edge, point;
};

Features featuresOf(const Plane& yy, int w, int h, const flip::FeatureFilters& f) {
    Plane lum(yy.size());
    for (size_t i = 0; i < yy.size(); ++i) lum[i] = (yy[i] + 16.0f) / 116.0f;  // Y/Yn in [0,1]
    const Plane ex = convolve(lum, w, h, f.first, f.gauss), ey = convolve(lum, w, h, f.gauss, f.first);
    const Plane px = convolve(lum, w, h, f.second, f.gauss), py = convolve(lum, w, h, f.gauss, f.second);
    Features out{Plane(yy.size()), Plane(yy.size())};
    for (size_t i = 0; i < yy.size(); ++i) {
        out.edge[i] = std::hypot(ex[i], ey[i]);
        out.point[i] = std::hypot(px[i], py[i]);
    }
    return out;
}

/// LDR-FLIP map of two RGB images already in [0,1].
Plane ldrFlipMap(const Rgb& test, const Rgb& ref, double ppd) {
    const int w = test.w, h = test.h;
    const auto yt = toYCxCz(test), yr = toYCxCz(ref);
    std::array<Plane, 3> ft, fr;
    for (int k = 0; k < 3; ++k) {
        ft[size_t(k)] = csfFilter(yt[size_t(k)], w, h, k, ppd);
        fr[size_t(k)] = csfFilter(yr[size_t(k)], w, h, k, ppd);
    }
    const flip::FeatureFilters filters = flip::featureFilters(ppd);
    const Features et = featuresOf(yt[0], w, h, filters), er = featuresOf(yr[0], w, h, filters);
    Plane out(test.valid.size());
    for (size_t p = 0; p < out.size(); ++p) {
        double rgbT[3], rgbR[3], labT[3], labR[3];
        fromYCxCz(ft[0][p], ft[1][p], ft[2][p], rgbT);
        fromYCxCz(fr[0][p], fr[1][p], fr[2][p], rgbR);
        flip::huntLab(rgbT[0], rgbT[1], rgbT[2], labT);
        flip::huntLab(rgbR[0], rgbR[1], rgbR[2], labR);
        const double colour = flip::remapColorError(std::pow(flip::hyab(labT, labR), flip::kQc));
        // §4.2.2, eq. 9: ΔE_f = (max(|edge difference|, |point difference|) / √2)^q_f.
        const double df = std::max(std::abs(et.edge[p] - er.edge[p]), std::abs(et.point[p] - er.point[p]));
        const double feature = std::pow(std::min(1.0, df / std::sqrt(2.0)), flip::kQf);
        out[p] = float(std::pow(colour, 1.0 - feature));  // §4.3, eq. 10
    }
    return out;
}

FlipResult resultOf(const Plane& map, const Rgb& test, const Rgb& ref) {
    FlipResult r;
    r.map = Image(test.w, test.h, 1);
    r.map.channelNames = {"FLIP"};
    double sum = 0;
    size_t n = 0;
    for (size_t p = 0; p < map.size(); ++p) {
        const bool ok = test.valid[p] && ref.valid[p];
        r.map.pixels[p] = ok ? map[p] : std::numeric_limits<float>::quiet_NaN();
        if (ok) sum += map[p], ++n;
    }
    r.mean = n ? sum / double(n) : std::numeric_limits<double>::quiet_NaN();
    return r;
}

void matchedRgb(const Image& test, const Image& ref, Rgb& t, Rgb& r) {
    std::vector<int> ct, cr;
    matchedChannels(test, ref, ct, cr);
    t = colourOf(test, ct);
    r = colourOf(ref, cr);
}

/// Each value mapped by f (clamping, exposure and tone mapping).
template <typename F>
Rgb mapped(const Rgb& in, F f) {
    Rgb out = in;
    for (float& x : out.v) x = float(f(double(x)));
    return out;
}

}  // namespace

FlipResult ldrFlip(const Image& test, const Image& ref, double ppd) {
    Rgb t, r;
    matchedRgb(test, ref, t, r);
    auto clamp01 = [](double x) { return std::clamp(x, 0.0, 1.0); };
    const Rgb tc = mapped(t, clamp01), rc = mapped(r, clamp01);
    return resultOf(ldrFlipMap(tc, rc, ppd), t, r);
}

FlipExposures hdrFlipExposures(const Image& ref) {
    const std::vector<int> ch = colourChannels(ref);
    const Rgb r = colourOf(ref, ch);
    std::vector<double> lum;
    double positiveMin = std::numeric_limits<double>::infinity();
    for (size_t p = 0; p < r.valid.size(); ++p) {
        if (!r.valid[p]) continue;
        const double y = 0.2126 * std::max(0.0f, r.v[3 * p]) + 0.7152 * std::max(0.0f, r.v[3 * p + 1]) +
                         0.0722 * std::max(0.0f, r.v[3 * p + 2]);
        lum.push_back(y);
        if (y > 0) positiveMin = std::min(positiveMin, y);
    }
    FlipExposures e;
    e.count = 2;
    if (lum.empty() || !std::isfinite(positiveMin)) return e;  // black: start = stop = 0
    const double yMax = *std::max_element(lum.begin(), lum.end());
    std::nth_element(lum.begin(), lum.begin() + long(lum.size() / 2), lum.end());
    const double yMedian = lum[lum.size() / 2] > 0 ? lum[lum.size() / 2] : positiveMin;
    const double x = flip::inverseToneMapAces(0.85);
    e.start = std::log2(x / yMax);
    e.stop = std::log2(x / yMedian);
    e.count = std::max(2, int(std::ceil(e.stop - e.start)));
    return e;
}

FlipResult hdrFlip(const Image& test, const Image& ref, double ppd) {
    Rgb t, r;
    matchedRgb(test, ref, t, r);
    const FlipExposures e = hdrFlipExposures(ref);
    Plane worst(t.valid.size(), 0.0f);
    for (int i = 0; i < e.count; ++i) {
        const double c = e.start + double(i) * (e.stop - e.start) / double(e.count - 1);
        const double scale = std::exp2(c);
        auto expose = [scale](double x) { return flip::toneMapAces(scale * std::max(0.0, x)); };
        const Plane m = ldrFlipMap(mapped(t, expose), mapped(r, expose), ppd);
        for (size_t p = 0; p < m.size(); ++p) worst[p] = std::max(worst[p], m[p]);
    }
    FlipResult out = resultOf(worst, t, r);
    out.exposures = e;
    return out;
}

}  // namespace iris
