#include "core/sampling.h"

#include <algorithm>

namespace iris {

Distribution1D::Distribution1D(std::span<const float> f) : func_(f.begin(), f.end()), cdf_(f.size() + 1) {
    const int n = int(f.size());
    for (float& v : func_) v = std::isfinite(v) ? std::abs(v) : 0.0f;
    cdf_[0] = 0;
    // Accumulate in double so long tables keep a monotone, accurate CDF.
    double acc = 0;
    std::vector<double> c(n + 1, 0.0);
    for (int i = 0; i < n; ++i) {
        acc += double(func_[i]) / n;
        c[i + 1] = acc;
    }
    funcInt_ = float(acc);
    for (int i = 1; i <= n; ++i) cdf_[i] = acc > 0 ? float(c[i] / acc) : float(i) / n;
    cdf_[n] = 1.0f;
    // Guide table (Chen & Asau 1974): guide_[b] = first CDF index with cdf > b/n, b = 0..n.
    guide_.resize(size_t(n) + 1);
    for (int b = 0; b <= n; ++b)
        guide_[b] = int(std::upper_bound(cdf_.begin(), cdf_.end(), float(b) / float(n)) - cdf_.begin());
}

int Distribution1D::findIntervalBinary(float u) const {
    // Largest index with cdf_[i] <= u.
    const auto it = std::upper_bound(cdf_.begin(), cdf_.end(), u);
    return std::clamp(int(it - cdf_.begin()) - 1, 0, count() - 1);
}

int Distribution1D::findInterval(float u) const {
    const int n = count();
    if (guide_.empty()) return findIntervalBinary(u);
    const float x = u * float(n);
    const int b = x >= 0.0f ? (x < float(n) ? int(x) : n - 1) : 0;
    // For u in [b/n, (b+1)/n) every CDF entry before guide_[b] is <= u and the entry at guide_[b+1]
    // (if any) is > u, so the first entry > u lies in [guide_[b], guide_[b+1]]. The two conditions
    // are checked (rounding of u·n, NaN); if either fails, the full search runs.
    const int lo = guide_[b], hi = guide_[b + 1];
    const int size = int(cdf_.size());
    if ((lo > 0 && !(cdf_[lo - 1] <= u)) || (hi < size && !(cdf_[hi] > u))) return findIntervalBinary(u);
    const auto it = std::upper_bound(cdf_.begin() + lo, cdf_.begin() + hi, u);
    return std::clamp(int(it - cdf_.begin()) - 1, 0, n - 1);
}

float Distribution1D::sampleContinuous(float u, float* pdf, int* offset) const {
    const int n = count();
    const int o = findInterval(u);
    if (offset) *offset = o;
    float du = u - cdf_[o];
    const float width = cdf_[o + 1] - cdf_[o];
    if (width > 0) du = std::min(du / width, kOneMinusEpsilon);
    if (pdf) *pdf = funcInt_ > 0 ? func_[o] / funcInt_ : 1.0f;
    return std::min((o + du) / n, kOneMinusEpsilon);
}

int Distribution1D::sampleDiscrete(float u, float* pmf, float* uRemapped) const {
    const int o = findInterval(u);
    if (pmf) *pmf = discretePmf(o);
    if (uRemapped) {
        const float width = cdf_[o + 1] - cdf_[o];
        *uRemapped = width > 0 ? std::min((u - cdf_[o]) / width, kOneMinusEpsilon) : 0.0f;
    }
    return o;
}

float Distribution1D::pdf(float x) const {
    if (funcInt_ <= 0) return 0;
    const int o = std::clamp(int(x * count()), 0, count() - 1);
    return func_[o] / funcInt_;
}

namespace {
// Density of texel (iu, iv): conditional pdf × marginal pdf, p(u|v) p(v) (pbrt-v4 §A.4.2).
float texelPdf(const Distribution1D& cond, const Distribution1D& marginal, int iu) {
    return cond.pdf((iu + 0.5f) / cond.count()) * cond.integral() / marginal.integral();
}
}  // namespace

Distribution2D::Distribution2D(std::span<const float> f, int nu, int nv) : nu_(nu), nv_(nv) {
    conditional_.reserve(nv);
    std::vector<float> marginal(nv);
    for (int v = 0; v < nv; ++v) {
        conditional_.emplace_back(f.subspan(size_t(v) * nu, nu));
        marginal[v] = conditional_.back().integral();
    }
    marginal_ = Distribution1D(marginal);
    // The piecewise-constant density, one value per texel (the same expression as pdfGeneral).
    pdf_.assign(size_t(nu) * nv, 0.0f);
    if (marginal_.integral() > 0)
        for (int v = 0; v < nv; ++v)
            for (int u = 0; u < nu; ++u) pdf_[size_t(v) * nu + u] = texelPdf(conditional_[v], marginal_, u);
}

vec2 Distribution2D::sampleContinuous(const vec2& u, float* pdf) const {
    float pdfs[2];
    int v;
    const float d1 = marginal_.sampleContinuous(u.y, &pdfs[1], &v);
    const float d0 = conditional_[v].sampleContinuous(u.x, &pdfs[0]);
    if (pdf) *pdf = pdfs[0] * pdfs[1];
    return vec2(d0, d1);
}

float Distribution2D::pdfGeneral(const vec2& p) const {
    const int nv = marginal_.count();
    const int iv = std::clamp(int(p.y * nv), 0, nv - 1);
    const auto& cond = conditional_[iv];
    const int iu = std::clamp(int(p.x * cond.count()), 0, cond.count() - 1);
    if (marginal_.integral() <= 0) return 0;
    return texelPdf(cond, marginal_, iu);
}

float Distribution2D::pdf(const vec2& p) const {
    if (pdf_.empty()) return 0.0f;
    // Same indices as pdfGeneral (every conditional has nu_ entries).
    const int iv = std::clamp(int(p.y * nv_), 0, nv_ - 1);
    const int iu = std::clamp(int(p.x * nu_), 0, nu_ - 1);
    return pdf_[size_t(iv) * nu_ + iu];
}

}  // namespace iris
