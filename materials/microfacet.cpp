#include "materials/microfacet.h"

#include "core/error.h"
#include "materials/textures/texture_params.h"

namespace iris {

namespace {
constexpr double kSqrtPi = 1.77245385090551602730;

/// α² tan²θ of direction w for the anisotropic α(φ) ([H14] eq. 80): (x² αx² + y² αy²) / z².
float alpha2Tan2(const vec3& w, float ax, float ay) {
    return (sqr(w.x * ax) + sqr(w.y * ay)) / sqr(w.z);
}
}  // namespace

MicrofacetType MicrofacetDistribution::parseType(const std::string& name) {
    if (name == "beckmann") return MicrofacetType::Beckmann;
    if (name == "ggx") return MicrofacetType::GGX;
    fail("unknown microfacet distribution '", name, "' (supported: beckmann, ggx)");
}

float MicrofacetDistribution::D(const vec3& m) const {
    if (m.z <= 0) return 0.0f;
    const float cos2 = m.z * m.z;
    // tan²θ (cos²φ/αx² + sin²φ/αy²) = (mx²/αx² + my²/αy²) / mz².
    const float q = sqr(m.x / ax_) + sqr(m.y / ay_);
    float d;
    if (type_ == MicrofacetType::Beckmann) {
        // thesis 000 eq. 2.10, [W07] eq. 25 (anisotropic form [H14] eq. 84)
        const float e = q / cos2;
        d = std::exp(-e) / (kPi * ax_ * ay_ * cos2 * cos2);
    } else {
        // [W07] eq. 33, [H14] eq. 85, multiplied out for a unit m so that it stays finite at the
        // horizon: cos⁴θ (1 + tan²θ(...))² = (mz² + mx²/αx² + my²/αy²)².
        d = 1.0f / (kPi * ax_ * ay_ * sqr(cos2 + q));
    }
    return std::isfinite(d) ? d : 0.0f;
}

namespace {
constexpr float kBeckmannNegligibleLambdaA2T2 = 0.08f;
float lambdaExact(MicrofacetType type, float a2t2) {
    if (type == MicrofacetType::GGX) return 0.5f * (-1.0f + std::sqrt(1.0f + a2t2));  // [H14] eq. 86
    // Beckmann, [H14] eq. 72 with a = 1/(α tanθ): Λ = (erf(a) − 1)/2 + exp(−a²)/(2a√π).
    // For a ≥ 3.53 (α² tan²θ ≤ 0.08) Λ ≤ 1.1e-8 < 2⁻²⁶: every use adds Λ to 1 in float
    // (G1 = 1/(1 + Λ), 1/(1 + Λi + Λo)), where it vanishes, so 0 gives the same results without the
    // erf and exp (tests/materials/test_microfacet.cpp, BeckmannLambdaCutoffChangesNoG1).
    if (a2t2 <= kBeckmannNegligibleLambdaA2T2) return 0.0f;
    const double a = 1.0 / std::sqrt(double(a2t2));
    return float(0.5 * (std::erf(a) - 1.0) + std::exp(-a * a) / (2.0 * a * kSqrtPi));
}
float lambdaRational(float a2t2) {
    // Rational fit of [W07] eq. 27 / thesis 000 eqs. 2.13–2.14 written as Λ so that
    // 1/(1+Λ) = (3.535a + 2.181a²)/(1 + 2.276a + 2.577a²) for a < 1.6, else G1 = 1.
    const float a = 1.0f / std::sqrt(a2t2);
    if (a >= 1.6f) return 0.0f;
    return (1.0f - 1.259f * a + 0.396f * a * a) / (3.535f * a + 2.181f * a * a);
}
}  // namespace

float MicrofacetDistribution::Lambda(const vec3& w) const {
    if (w.z == 0) return 1e30f;
    const float a2t2 = alpha2Tan2(w, ax_, ay_);
    if (!(a2t2 > 0)) return 0.0f;  // normal direction (or NaN guard)
    if (!std::isfinite(a2t2)) return 1e30f;
    return lambdaExact(type_, a2t2);
}

float MicrofacetDistribution::smithG1(const vec3& w, const vec3& m) const {
    if (glm::dot(w, m) * w.z <= 0) return 0.0f;  // χ+((w·m)/(w·n))
    return 1.0f / (1.0f + Lambda(w));
}

float MicrofacetDistribution::G1(const vec3& w, const vec3& m) const {
    if (type_ != MicrofacetType::Beckmann || !rational_) return smithG1(w, m);
    if (glm::dot(w, m) * w.z <= 0) return 0.0f;
    if (w.z == 0) return 0.0f;
    const float a2t2 = alpha2Tan2(w, ax_, ay_);
    if (!(a2t2 > 0)) return 1.0f;
    // Thesis 000 eq. 2.13 with a = 1/(α tanθ) (eq. 2.14).
    const float a = 1.0f / std::sqrt(a2t2);
    if (a >= 1.6f) return 1.0f;
    return (3.535f * a + 2.181f * a * a) / (1.0f + 2.276f * a + 2.577f * a * a);
}

float MicrofacetDistribution::G(const vec3& wi, const vec3& wo, const vec3& m) const {
    switch (shadowing_) {
        case ShadowingModel::SmithSeparable:
            return G1(wi, m) * G1(wo, m);  // thesis 000 eq. 2.12
        case ShadowingModel::SmithHeightCorrelated: {
            if (glm::dot(wi, m) * wi.z <= 0 || glm::dot(wo, m) * wo.z <= 0) return 0.0f;
            float li, lo;
            if (type_ == MicrofacetType::Beckmann && rational_) {
                li = wi.z == 0 ? 1e30f : lambdaRational(alpha2Tan2(wi, ax_, ay_));
                lo = wo.z == 0 ? 1e30f : lambdaRational(alpha2Tan2(wo, ax_, ay_));
            } else {
                li = Lambda(wi);
                lo = Lambda(wo);
            }
            return 1.0f / (1.0f + li + lo);  // [H14] eq. 99
        }
        case ShadowingModel::VCavity: {
            if (glm::dot(wi, m) * wi.z <= 0 || glm::dot(wo, m) * wo.z <= 0) return 0.0f;
            // Cook & Torrance 1982 eq. (G term), thesis 003:
            // G = min(1, 2(n·h)(n·v)/(v·h), 2(n·h)(n·l)/(v·h)); v·h = l·h for reflection.
            const float nh = std::abs(m.z);
            const float go = 2.0f * nh * std::abs(wo.z) / std::abs(glm::dot(wo, m));
            const float gi = 2.0f * nh * std::abs(wi.z) / std::abs(glm::dot(wi, m));
            return std::min(1.0f, std::min(go, gi));
        }
    }
    return 0.0f;
}

vec3 MicrofacetDistribution::sampleAllNormals(const vec2& u) const {
    // Sample the slope distribution P22 directly (equivalent to thesis 000 eq. 2.19 for isotropic
    // Beckmann, tanθ = α sqrt(−log(1−ξ1)), φ = 2πξ2; GGX: tan²θ = α² ξ1/(1−ξ1), [W07] eq. 35).
    // Anisotropy by stretching the α = 1 slopes by (αx, αy) ([H14] §5.3).
    const float u1 = std::min(u.x, 1.0f - 1e-7f);
    const float r2 = type_ == MicrofacetType::Beckmann ? -std::log(1.0f - u1) : u1 / (1.0f - u1);
    const float r = std::sqrt(r2);
    const float phi = 2.0f * kPi * u.y;
    const float sx = ax_ * r * std::cos(phi), sy = ay_ * r * std::sin(phi);
    return glm::normalize(vec3(-sx, -sy, 1.0f));
}

vec3 MicrofacetDistribution::sampleVisibleGGX(const vec3& wo, const vec2& u) const {
    // Heitz 2018, listing 1: stretch, sample the projected hemisphere, unstretch.
    const vec3 vh = glm::normalize(vec3(ax_ * wo.x, ay_ * wo.y, wo.z));
    const float lensq = vh.x * vh.x + vh.y * vh.y;
    const vec3 t1 = lensq > 0 ? vec3(-vh.y, vh.x, 0.0f) / std::sqrt(lensq) : vec3(1, 0, 0);
    const vec3 t2 = glm::cross(vh, t1);
    const float r = std::sqrt(u.x);
    const float phi = 2.0f * kPi * u.y;
    const float p1 = r * std::cos(phi);
    float p2 = r * std::sin(phi);
    const float s = 0.5f * (1.0f + vh.z);
    p2 = (1.0f - s) * std::sqrt(std::max(0.0f, 1.0f - p1 * p1)) + s * p2;
    const vec3 nh = p1 * t1 + p2 * t2 + std::sqrt(std::max(0.0f, 1.0f - p1 * p1 - p2 * p2)) * vh;
    return glm::normalize(vec3(ax_ * nh.x, ay_ * nh.y, std::max(1e-6f, nh.z)));
}

double erfInv(double x) {
    if (x <= -1.0) return -INFINITY;
    if (x >= 1.0) return INFINITY;
    // Giles 2010, single-precision approximation (published coefficients).
    const float xf = float(x);
    float w = -std::log((1.0f - xf) * (1.0f + xf)), p;
    if (w < 5.0f) {
        w -= 2.5f;
        p = 2.81022636e-08f;
        p = 3.43273939e-07f + p * w;
        p = -3.5233877e-06f + p * w;
        p = -4.39150654e-06f + p * w;
        p = 0.00021858087f + p * w;
        p = -0.00125372503f + p * w;
        p = -0.00417768164f + p * w;
        p = 0.246640727f + p * w;
        p = 1.50140941f + p * w;
    } else {
        w = std::sqrt(w) - 3.0f;
        p = -0.000200214257f;
        p = 0.000100950558f + p * w;
        p = 0.00134934322f + p * w;
        p = -0.00367342844f + p * w;
        p = 0.00573950773f + p * w;
        p = -0.0076224613f + p * w;
        p = 0.00943887047f + p * w;
        p = 1.00167406f + p * w;
        p = 2.83297682f + p * w;
    }
    double y = double(p) * x;
    if (!std::isfinite(y)) return y;
    for (int i = 0; i < 2; ++i) {  // Newton on erf(y) = x: erf'(y) = 2/√π e^{−y²}
        const double d = 2.0 / kSqrtPi * std::exp(-y * y);
        if (d <= 0) break;
        y -= (std::erf(y) - x) / d;
    }
    return y;
}

namespace {
/// Sample the x slope of the visible Beckmann slopes for α = 1 and an incident direction at
/// polar angle θ in the xz plane ([HD14] §4): density ∝ (cosθ − x sinθ) e^{−x²} on x < cotθ, so
///   CDF(x) ∝ cosθ (1 + erf x)/2 + sinθ e^{−x²}/(2√π).
/// Inverted numerically with a bracketed Newton iteration in double precision.
double sampleBeckmannVisibleSlopeX(double cosT, double sinT, double u) {
    auto cdf = [&](double x) { return 0.5 * cosT * (1.0 + std::erf(x)) + sinT * std::exp(-x * x) / (2.0 * kSqrtPi); };
    double lo = -8.0, hi = 8.0;
    if (sinT > 0) hi = std::min(hi, cosT / sinT);
    const double flo = cdf(lo), fhi = cdf(hi);
    const double target = flo + u * (fhi - flo);
    double x = std::clamp(erfInv(std::clamp(2.0 * u - 1.0, -1.0 + 1e-12, 1.0 - 1e-12)), lo, hi);
    for (int it = 0; it < 100; ++it) {
        const double f = cdf(x) - target;
        if (f > 0) hi = x; else lo = x;
        const double dens = (cosT - x * sinT) * std::exp(-x * x) / kSqrtPi;
        double xn = dens > 0 ? x - f / dens : 0.5 * (lo + hi);
        if (!(xn > lo && xn < hi)) xn = 0.5 * (lo + hi);
        if (std::abs(xn - x) < 1e-10 || hi - lo < 1e-12) return xn;
        x = xn;
    }
    return x;
}
}  // namespace

vec3 MicrofacetDistribution::sampleVisibleBeckmann(const vec3& wo, const vec2& u) const {
    // [HD14]: stretch wo to the α = 1 configuration, sample the visible slopes there, rotate by
    // the azimuth of the stretched wo, unstretch, and turn the slope into a normal.
    const vec3 v = glm::normalize(vec3(ax_ * wo.x, ay_ * wo.y, wo.z));
    const double cosT = std::clamp(double(v.z), 0.0, 1.0);
    const double sinT = std::sqrt(std::max(0.0, 1.0 - cosT * cosT));
    double cosP = 1, sinP = 0;
    const double rxy = std::sqrt(double(v.x) * v.x + double(v.y) * v.y);
    if (rxy > 0) {
        cosP = v.x / rxy;
        sinP = v.y / rxy;
    }
    const double sx = sampleBeckmannVisibleSlopeX(cosT, sinT, u.x);
    const double sy = erfInv(std::clamp(2.0 * u.y - 1.0, -1.0 + 1e-12, 1.0 - 1e-12));
    const double x = (cosP * sx - sinP * sy) * ax_;
    const double y = (sinP * sx + cosP * sy) * ay_;
    return glm::normalize(vec3(float(-x), float(-y), 1.0f));
}

vec3 MicrofacetDistribution::sampleNormal(const vec3& wo, const vec2& u) const {
    if (!sampleVisible_) return sampleAllNormals(u);
    const vec3 w = wo.z < 0 ? -wo : wo;
    return type_ == MicrofacetType::GGX ? sampleVisibleGGX(w, u) : sampleVisibleBeckmann(w, u);
}

float MicrofacetDistribution::pdf(const vec3& wo, const vec3& m) const {
    if (!sampleVisible_) return D(m) * std::max(0.0f, m.z);
    const vec3 w = wo.z < 0 ? -wo : wo;
    if (w.z == 0) return 0.0f;
    return smithG1(w, m) * std::max(0.0f, glm::dot(w, m)) * D(m) / w.z;  // [HD14] eq. 2
}


MicrofacetParams MicrofacetParams::read(const Properties& p, const std::string& defaultDistribution, float defaultAlpha) {
    MicrofacetParams mp;
    const std::string dist = p.getString("distribution", defaultDistribution);
    mp.type = withLocation(p.locationOf("distribution"), [&] { return MicrofacetDistribution::parseType(dist); });
    const bool aniso = p.has("alpha_u") || p.has("alpha_v");
    if (aniso) {
        if (p.has("alpha")) failAt(p.locationOf("alpha"), "give either 'alpha' or 'alpha_u'/'alpha_v', not both");
        mp.alphaU = getFloatTexture(p, "alpha_u");
        mp.alphaV = getFloatTexture(p, "alpha_v");
    } else {
        mp.alphaU = mp.alphaV = getFloatTexture(p, "alpha", defaultAlpha);
    }
    mp.sampleVisible = p.getBool("sample_visible", true);
    const std::string masking = p.getString("masking", "separable");
    if (masking == "separable")
        mp.shadowing = ShadowingModel::SmithSeparable;
    else if (masking == "height_correlated")
        mp.shadowing = ShadowingModel::SmithHeightCorrelated;
    else if (masking == "vcavity")
        mp.shadowing = ShadowingModel::VCavity;
    else
        failAt(p.locationOf("masking"), "unknown masking '", masking, "' (supported: separable, height_correlated, vcavity)");
    mp.rational = p.getBool("beckmann_rational_g1", false);
    return mp;
}

}  // namespace iris
