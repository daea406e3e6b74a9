#include "tests/support/agreement.h"

#include <cmath>
#include <sstream>

namespace iris::test {

double normalQuantileTwoSided(double p) {
    double lo = 0, hi = 40;  // P(|Z| > z) = erfc(z / √2), decreasing in z
    for (int i = 0; i < 200; ++i) {
        const double mid = 0.5 * (lo + hi);
        (std::erfc(mid / std::sqrt(2.0)) > p ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

namespace {

struct BlockStats {
    double mean = 0, var = 0;
};

BlockStats blockStats(const std::vector<float>& mean, const std::vector<float>& var, int width, int x0, int y0, int w, int h, int c) {
    BlockStats s;
    for (int y = y0; y < y0 + h; ++y)
        for (int x = x0; x < x0 + w; ++x) {
            const size_t i = 3 * (size_t(y) * size_t(width) + size_t(x)) + size_t(c);
            s.mean += mean[i];
            s.var += var[i];
        }
    const double n = double(w) * h;
    s.mean /= n;
    s.var /= n * n;
    return s;
}

}  // namespace

Agreement compareFilms(const Film& test, const Film& ref, int block, double alpha) {
    return compareFilms(test, ref, PixelRect{0, 0, test.width(), test.height()}, block, alpha);
}

Agreement compareFilms(const Film& test, const Film& ref, const PixelRect& rect, int block, double alpha) {
    const int W = test.width();
    const std::vector<float> mt = test.meanImage(), vt = test.varianceOfMeanImage();
    const std::vector<float> mr = ref.meanImage(), vr = ref.varianceOfMeanImage();
    struct Region {
        int x, y, w, h;
    };
    std::vector<Region> regions;
    for (int y = rect.y0; y + block <= rect.y1; y += block)
        for (int x = rect.x0; x + block <= rect.x1; x += block) regions.push_back({x, y, block, block});
    regions.push_back({rect.x0, rect.y0, rect.x1 - rect.x0, rect.y1 - rect.y0});
    Agreement a;
    a.tests = int(regions.size()) * 3;
    a.threshold = normalQuantileTwoSided(1.0 - std::pow(1.0 - alpha, 1.0 / a.tests));
    for (const Region& r : regions)
        for (int c = 0; c < 3; ++c) {
            const BlockStats t = blockStats(mt, vt, W, r.x, r.y, r.w, r.h, c), f = blockStats(mr, vr, W, r.x, r.y, r.w, r.h, c);
            const double d = t.mean - f.mean, v = t.var + f.var;
            const double z = v > 0 ? std::abs(d) / std::sqrt(v) : (std::abs(d) <= 1e-6 * std::abs(f.mean) ? 0.0 : INFINITY);
            if (z > a.maxAbsZ) {
                std::ostringstream os;
                os << "block (" << r.x << ", " << r.y << ") " << r.w << "x" << r.h << " channel " << c << ": " << t.mean << " vs "
                   << f.mean << " (ratio " << t.mean / f.mean << ")";
                a.maxAbsZ = z;
                a.where = os.str();
            }
        }
    return a;
}

}  // namespace iris::test
