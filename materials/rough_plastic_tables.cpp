// Rough dielectric transmittance tables (see rough_plastic_tables.h).
#include "materials/rough_plastic_tables.h"

#include <tbb/parallel_for.h>

#include <array>
#include <atomic>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <mutex>

#include <unistd.h>

#include "core/error.h"
#include "core/io/atomic_file.h"
#include "core/io/output_file.h"
#include "core/quadrature.h"
#include "materials/fresnel.h"

namespace iris {
namespace {

constexpr uint32_t kFormatVersion = 2;  // 2: η = 1 node at 1 + 1e-4
constexpr char kMagic[8] = {'I', 'R', 'I', 'S', 'R', 'P', 'T', 'B'};

/// tan²θh of the microfacet normal at CDF value u of D(m) cosθm (thesis eq. 2.19 for Beckmann;
/// Walter et al. 2007 eq. 35 for GGX) and the inverse.
double tan2FromCdf(MicrofacetType t, double alpha, double u) {
    if (t == MicrofacetType::Beckmann) return -alpha * alpha * std::log1p(-u);
    return alpha * alpha * u / (1.0 - u);
}
double cdfFromTan2(MicrofacetType t, double alpha, double tan2) {
    if (t == MicrofacetType::Beckmann) return -std::expm1(-tan2 / (alpha * alpha));
    return tan2 / (alpha * alpha + tan2);
}

/// Smooth-interface transmittance 1 − F(μ) (the α → 0 limit).
double smoothTransmittance(double eta, double mu) { return 1.0 - fresnelDielectric(float(mu), float(eta)); }

}  // namespace

namespace {

enum class InterfaceLobe { Transmission, Reflection };

/// ∫₀^φmax of the reflection integrand (i·m)/(μ cosθm) F(i·m) G1(o, m) dφ at one θm. The integrand
/// has kinks where i·m = μ cosθm + sinθi sinθm cos φ crosses the critical angle (η < 1: F reaches 1)
/// and where the reflected o = 2(i·m)m − i crosses the horizon (o.z = 2(i·m) cosθm − μ = 0): the
/// φ-range is split there, q Gauss-Legendre points per piece.
double reflectionOverPhi(const MicrofacetDistribution& dist, const vec3& wi, double sinI, double mu, double sinM,
                         double cosM, double phiMax, double eta, const GaussLegendre& gl) {
    double cuts[4] = {0.0, phiMax, phiMax, phiMax};
    int n = 1;
    const auto cutAt = [&](double im) {  // φ where i·m = im (i·m decreases with φ on [0, π])
        if (!(sinI * sinM > 0)) return;
        const double c = (im - mu * cosM) / (sinI * sinM);
        if (!(c > -1.0 && c < 1.0)) return;
        const double phi = std::acos(c);
        if (phi > 0.0 && phi < phiMax) cuts[n++] = phi;
    };
    if (eta < 1.0) cutAt(std::sqrt(1.0 - eta * eta));  // cosθc of total internal reflection
    cutAt(mu / (2.0 * cosM));
    cuts[n++] = phiMax;
    std::sort(cuts, cuts + n);
    double sum = 0;
    for (int piece = 0; piece + 1 < n; ++piece) {
        const double a = cuts[piece], len = cuts[piece + 1] - a;
        if (!(len > 0)) continue;
        for (size_t b = 0; b < gl.x.size(); ++b) {
            const double phi = a + len * gl.x[b];
            const vec3 m(float(sinM * std::cos(phi)), float(sinM * std::sin(phi)), float(cosM));
            const double im = sinI * sinM * std::cos(phi) + mu * cosM;
            if (im <= 0) continue;
            const double g1o = dist.smithG1(reflect(wi, m), m);
            sum += len * gl.w[b] * im / (mu * cosM) * double(fresnelDielectric(float(im), float(eta))) * g1o;
        }
    }
    return sum;
}

/// Directional transmittance or reflectance of the rough interface lit at cosθi = μ (shared by
/// roughTransmittanceIntegral and roughReflectanceIntegral).
double roughInterfaceIntegral(MicrofacetType type, double eta, double alpha, double mu, int q, InterfaceLobe lobe) {
    mu = std::clamp(mu, 1e-4, 1.0);  // μ = 0 is read as its limit (T is linear near grazing)
    if (alpha <= 0) {
        const double t = smoothTransmittance(eta, mu);
        return lobe == InterfaceLobe::Transmission ? t : 1.0 - t;
    }
    const MicrofacetDistribution dist(type, float(alpha), float(alpha));
    const double sinI = std::sqrt(std::max(0.0, 1.0 - mu * mu));
    const vec3 wi(float(sinI), 0.0f, float(mu));
    const double g1i = dist.smithG1(wi, vec3(0, 0, 1));
    const GaussLegendre& gl = gaussLegendre(q);
    // T = ∫ G1(i) (i·m)₊ D(m)/μ (1 − F(i·m)) G1(o, m) dωm, o = refract(i, m)  (Walter 2007 eqs.
    // 21, 23 with the change of variables dωo → dωm); with m ~ D(m) cosθm (CDF u, φ):
    // T = ∫du (1/π) ∫₀^φmax G1(i) (i·m)/(μ cosθm) (1 − F) G1(o) dφ.
    // R is the same with F(i·m) and o = reflect(i, m) (Walter 2007 eqs. 20, 23; G1(o, m) = 0 when
    // o falls below the surface).
    // The visible range of φ is all of [0, π] while θm ≤ θ* = π/2 − θi, and |φ| ≤ φmax(θm) after:
    // split the u-range at θ* so that each piece is smooth.
    const double thetaStar = M_PI / 2 - std::acos(mu);
    const double uStar = thetaStar >= M_PI / 2 ? 1.0 : cdfFromTan2(type, alpha, sqr(std::tan(thetaStar)));
    double total = 0;
    for (int piece = 0; piece < 2; ++piece) {
        const double u0 = piece == 0 ? 0.0 : uStar, u1 = piece == 0 ? uStar : 1.0;
        if (!(u1 > u0)) continue;
        for (int a = 0; a < q; ++a) {
            // u = u1 − (u1 − u0)(1 − w)²: removes the integrable tail singularity at u → 1.
            const double w = gl.x[a];
            const double u = u1 - (u1 - u0) * sqr(1.0 - w);
            const double du = 2.0 * (u1 - u0) * (1.0 - w) * gl.w[a];
            const double tan2 = tan2FromCdf(type, alpha, u);
            if (!std::isfinite(tan2)) continue;
            const double cosM = 1.0 / std::sqrt(1.0 + tan2), sinM = std::sqrt(tan2) * cosM;
            double phiMax = M_PI;
            if (piece == 1 && sinI > 0 && sinM > 0) phiMax = std::acos(std::clamp(-(mu * cosM) / (sinI * sinM), -1.0, 1.0));
            if (lobe == InterfaceLobe::Reflection) {
                total += du * reflectionOverPhi(dist, wi, sinI, mu, sinM, cosM, phiMax, eta, gl) / M_PI;
                continue;
            }
            double inner = 0;
            for (int b = 0; b < q; ++b) {
                const double phi = phiMax * gl.x[b];
                const vec3 m(float(sinM * std::cos(phi)), float(sinM * std::sin(phi)), float(cosM));
                const double im = sinI * sinM * std::cos(phi) + mu * cosM;
                if (im <= 0) continue;
                const FresnelDielectricResult fr = fresnelDielectricFull(float(im), float(eta));
                if (fr.R >= 1.0f) continue;  // total internal reflection on this facet
                const vec3 wo = refract(wi, m, fr.cosThetaT, fr.etaTI);
                const double g1o = dist.smithG1(wo, m);
                inner += gl.w[b] * im / (mu * cosM) * (1.0 - fr.R) * g1o;
            }
            total += du * inner * phiMax / M_PI;
        }
    }
    return total * g1i;
}

}  // namespace

double roughTransmittanceIntegral(MicrofacetType type, double eta, double alpha, double mu, int q) {
    return roughInterfaceIntegral(type, eta, alpha, mu, q, InterfaceLobe::Transmission);
}

double roughReflectanceIntegral(MicrofacetType type, double eta, double alpha, double mu, int q) {
    return roughInterfaceIntegral(type, eta, alpha, mu, q, InterfaceLobe::Reflection);
}

double mitsuba3InternalReflectance(MicrofacetType type, double eta, double alpha, int q) {
    // Mitsuba 3, src/bsdfs/roughplastic.cpp (parameters_changed): m_internal_reflectance =
    // 2 · mean(R(μ_k, 1/η) μ_k) over the 64 directions μ_k = max(10⁻⁶, k/63) of its transmittance
    // table, R the directional reflectance of the rough interface seen from inside (light in the
    // denser medium; total internal reflection on the facets beyond the critical angle).
    constexpr int kNodes = kMitsuba3TransmittanceNodes;
    double sum = 0;
    for (int k = 0; k < kNodes; ++k) {
        const double mu = std::max(1e-6, double(k) / double(kNodes - 1));
        sum += roughReflectanceIntegral(type, 1.0 / eta, alpha, mu, q) * mu;
    }
    return 2.0 * sum / kNodes;
}

double roughInternalDiffuseIntegral(MicrofacetType type, double eta, double alpha, int q, int qMu) {
    const GaussLegendre& gl = gaussLegendre(qMu);
    double s = 0;
    for (int k = 0; k < qMu; ++k) s += gl.w[k] * gl.x[k] * roughTransmittanceIntegral(type, eta, alpha, gl.x[k], q);
    return 2.0 * s / (eta * eta);
}

RoughTransmittanceTables buildRoughTables(MicrofacetType type, const RoughTableResolution& res) {
    if (res.nEta < 2 || res.nAlpha < 2 || res.nMu < 2) fail("rough plastic tables need at least 2 nodes per axis");
    RoughTransmittanceTables t;
    t.type = type;
    t.res = res;
    t.ext.assign(size_t(res.nEta) * res.nAlpha * res.nMu, 0.0f);
    t.diffuse.assign(size_t(res.nEta) * res.nAlpha, 0.0f);
    const int lines = res.nEta * res.nAlpha;
    tbb::parallel_for(0, lines, [&](int line) {
        const int ie = line / res.nAlpha, ia = line % res.nAlpha;
        // The η = 1 node is evaluated at 1 + 1e-4: T is discontinuous at (η → 1⁺, μ → 0) (grazing
        // Fresnel reflectance → 1 for any η > 1, but 0 at η = 1), and the one-sided limit keeps
        // specular + diffuse energy ≤ 1 for index-matched-ish coats at grazing angles.
        const double eta = std::max(double(RoughTransmittanceTables::etaNode(ie, res.nEta)), 1.0 + 1e-4);
        const double alpha = RoughTransmittanceTables::alphaNode(ia, res.nAlpha);
        for (int im = 0; im < res.nMu; ++im)
            t.ext[size_t(line) * res.nMu + im] = float(std::clamp(
                roughTransmittanceIntegral(type, eta, alpha, RoughTransmittanceTables::muNode(im, res.nMu), res.quadrature),
                0.0, 1.0));  // quadrature error can exceed 1 by ~1e-7
        t.diffuse[line] =
            float(std::clamp(roughInternalDiffuseIntegral(type, eta, alpha, res.quadrature, res.quadrature), 0.0, 1.0));
    });
    return t;
}

// ---- Catmull-Rom interpolation (thesis eqs. 2.45–2.50) ----

namespace {

float etaCoord(float eta, int n) {
    using T = RoughTransmittanceTables;
    return std::sqrt(std::clamp((eta - T::kEtaMin) / (T::kEtaMax - T::kEtaMin), 0.0f, 1.0f)) * float(n - 1);
}
float alphaCoord(float alpha, int n) {
    return std::sqrt(std::clamp(alpha, 0.0f, RoughTransmittanceTables::kAlphaMax) / RoughTransmittanceTables::kAlphaMax) *
           float(n - 1);
}

}  // namespace

RoughTransmittanceTables::Line RoughTransmittanceTables::line(float eta, float alpha) const {
    const RoughStencil se = roughCatmullRom(etaCoord(eta, res.nEta), res.nEta);
    const RoughStencil sa = roughCatmullRom(alphaCoord(alpha, res.nAlpha), res.nAlpha);
    Line l;
    for (int i = 0; i < se.count; ++i)
        for (int j = 0; j < sa.count; ++j) {
            l.offset[l.count] = (se.idx[i] * res.nAlpha + sa.idx[j]) * res.nMu;
            l.weight[l.count++] = se.w[i] * sa.w[j];
        }
    return l;
}

float RoughTransmittanceTables::transmittance(const Line& l, float cosTheta) const {
    const RoughStencil sm = roughMuStencil(cosTheta, res.nMu);
    float v = 0;  // eq. 2.44
    for (int i = 0; i < l.count; ++i) {
        const float* row = &ext[size_t(l.offset[i])];
        float lv = 0;
        for (int k = 0; k < sm.count; ++k) lv += sm.w[k] * row[sm.idx[k]];
        v += l.weight[i] * lv;
    }
    return std::clamp(v, 0.0f, 1.0f);
}

float RoughTransmittanceTables::internalDiffuseTransmittance(float eta, float alpha) const {
    const RoughStencil se = roughCatmullRom(etaCoord(eta, res.nEta), res.nEta);
    const RoughStencil sa = roughCatmullRom(alphaCoord(alpha, res.nAlpha), res.nAlpha);
    float v = 0;  // eq. 2.51
    for (int i = 0; i < se.count; ++i)
        for (int j = 0; j < sa.count; ++j) v += se.w[i] * sa.w[j] * diffuse[size_t(se.idx[i]) * res.nAlpha + sa.idx[j]];
    return std::clamp(v, 0.0f, 1.0f);
}

Mitsuba3InternalReflectanceCurve::Mitsuba3InternalReflectanceCurve(MicrofacetType type, float eta, int nAlpha, int q)
    : nodes_(size_t(std::max(nAlpha, 2)), 0.0f) {
    const int n = int(nodes_.size());
    tbb::parallel_for(0, n, [&](int k) {
        nodes_[size_t(k)] = float(mitsuba3InternalReflectance(type, eta, RoughTransmittanceTables::alphaNode(k, n), q));
    });
}

float Mitsuba3InternalReflectanceCurve::at(float alpha) const {
    const int n = int(nodes_.size());
    const RoughStencil s = roughCatmullRom(alphaCoord(alpha, n), n);
    float v = 0;
    for (int i = 0; i < s.count; ++i) v += s.w[i] * nodes_[size_t(s.idx[i])];
    return std::clamp(v, 0.0f, 1.0f);
}

RoughTablesAtAlpha::RoughTablesAtAlpha(const RoughTransmittanceTables& t, float alpha)
    : alpha_(alpha), nEta_(t.res.nEta), nMu_(t.res.nMu) {
    const RoughStencil sa = roughCatmullRom(alphaCoord(alpha, t.res.nAlpha), t.res.nAlpha);
    ext_.assign(size_t(nEta_) * nMu_, 0.0f);
    diffuse_.assign(size_t(nEta_), 0.0f);
    for (int i = 0; i < nEta_; ++i) {
        float* out = &ext_[size_t(i) * nMu_];
        for (int j = 0; j < sa.count; ++j) {
            const size_t cell = size_t(i) * t.res.nAlpha + sa.idx[j];
            const float* row = &t.ext[cell * nMu_];
            for (int m = 0; m < nMu_; ++m) out[m] += sa.w[j] * row[m];
            diffuse_[i] += sa.w[j] * t.diffuse[cell];
        }
    }
}

RoughStencil RoughTablesAtAlpha::etaStencil(float eta) const { return roughCatmullRom(etaCoord(eta, nEta_), nEta_); }

void RoughTablesAtAlpha::etaStencils(const float* eta, int n, RoughStencil* se, float* td, RoughEtaRows* rows) const {
    // Lane-wise the scalar etaCoord, roughCatmullRom (eqs. 2.45–2.49, interior branch) and
    // diffuse (eq. 2.51), in lanes of spectral/lanes.h (element-wise IEEE operations; the square
    // root correctly rounded, as std::sqrt).
    using lanes::Float4;
    using lanes::Int4;
    using T = RoughTransmittanceTables;
    const Float4 zero = lanes::broadcast(0.0f), one = lanes::broadcast(1.0f);
    const float last = float(nEta_ - 1);
    const Float4 lastV = lanes::broadcast(last);
    int c = 0;
    for (; c + 4 <= n; c += 4) {
        const Float4 u = lanes::clamp((lanes::load(eta + c) - T::kEtaMin) / (T::kEtaMax - T::kEtaMin), zero, one);
        const Float4 x = lanes::clamp(lanes::sqrt(u) * last, zero, lastV);  // etaCoord, then roughCatmullRom's clamp
        const Int4 i = lanes::min(lanes::toInt(x), lanes::broadcast(nEta_ - 2));  // std::min(int(x), n − 2)
        const Float4 t = x - lanes::toFloat(i), t2 = t * t, t3 = t2 * t;
        const Float4 w[4] = {-0.5f * t + t2 - 0.5f * t3,        // eq. 2.46
                             1.0f - 2.5f * t2 + 1.5f * t3,      // eq. 2.47
                             0.5f * t + 2.0f * t2 - 1.5f * t3,  // eq. 2.48
                             -0.5f * t2 + 0.5f * t3};           // eq. 2.49
        // Lanes to plain arrays for the per-lane gathers and stores (element access to vector
        // registers compiles to long shuffle sequences).
        int iv[4];
        float wv[4][4];  // wv[m][k]: weight of node i − 1 + m, lane k
        lanes::store(iv, i);
        for (int m = 0; m < 4; ++m) lanes::store(wv[m], w[m]);
        bool interior[4];
        float tdn[4][4] = {};  // tdn[m][k]: Td of node i − 1 + m, lane k
        for (int k = 0; k < 4; ++k) {
            interior[k] = iv[k] >= 1 && iv[k] + 2 <= nEta_ - 1;
            if (interior[k])
                for (int m = 0; m < 4; ++m) tdn[m][k] = diffuse_[size_t(iv[k] - 1 + m)];
        }
        Float4 d = zero;
        for (int m = 0; m < 4; ++m) d = d + w[m] * lanes::load(tdn[m]);  // diffuse: Σ w_m Td[i − 1 + m] in order
        float dv[4];
        lanes::store(dv, d);
        for (int k = 0; k < 4; ++k) {
            RoughStencil& s = se[c + k];
            if (!interior[k]) {  // ghost nodes (or NaN): the scalar code
                s = etaStencil(eta[c + k]);
                td[c + k] = diffuse(s);
                if (rows) rows[c + k].row = nullptr;
                continue;
            }
            td[c + k] = std::clamp(dv[k], 0.0f, 1.0f);
            if (!rows) {
                for (int m = 0; m < 4; ++m) {
                    s.idx[m] = iv[k] - 1 + m;
                    s.w[m] = wv[m][k];
                }
                s.count = 4;
            } else {  // the prepared rows replace se[c + k] (transmittances reads se only where row == nullptr)
                RoughEtaRows& r = rows[c + k];
                r.row = &ext_[size_t(iv[k] - 1) * size_t(nMu_)];
                for (int m = 0; m < 4; ++m) {
                    const float wm = wv[m][k];
                    r.w[m] = lanes::broadcast(wm);
                }
            }
        }
    }
    for (; c < n; ++c) {
        se[c] = etaStencil(eta[c]);
        td[c] = diffuse(se[c]);
        if (rows) rows[c].row = nullptr;  // transmittances() takes the scalar path for these
    }
}

float RoughTablesAtAlpha::collapse(float eta, float* line) const {
    const RoughStencil se = etaStencil(eta);
    for (int m = 0; m < nMu_; ++m) line[m] = lineNode(se, m);
    return diffuse(se);
}

// ---- Disk cache ----

namespace {

uint64_t fnv1a(const void* data, size_t n, uint64_t h = 1469598103934665603ull) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < n; ++i) h = (h ^ p[i]) * 1099511628211ull;
    return h;
}

struct Header {
    char magic[8];
    uint32_t version, type;
    int32_t nEta, nAlpha, nMu, quadrature;
    float etaMin, etaMax, alphaMax, pad;
};

const char* typeName(MicrofacetType t) { return t == MicrofacetType::Beckmann ? "beckmann" : "ggx"; }

}  // namespace

std::optional<RoughTransmittanceTables> readRoughTables(const std::string& path, MicrofacetType type,
                                                        const RoughTableResolution& res, std::string* why) {
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        if (why) *why = "missing";
        return std::nullopt;
    }
    Header h{};
    in.read(reinterpret_cast<char*>(&h), sizeof(h));
    if (!in || std::memcmp(h.magic, kMagic, 8) != 0 || h.version != kFormatVersion) {
        if (why) *why = "bad header";
        return std::nullopt;
    }
    using T = RoughTransmittanceTables;
    if (h.type != uint32_t(type) || h.nEta != res.nEta || h.nAlpha != res.nAlpha || h.nMu != res.nMu ||
        h.quadrature != res.quadrature || h.etaMin != T::kEtaMin || h.etaMax != T::kEtaMax || h.alphaMax != T::kAlphaMax) {
        if (why) *why = "parameters do not match";
        return std::nullopt;
    }
    RoughTransmittanceTables t;
    t.type = type;
    t.res = res;
    t.ext.resize(size_t(res.nEta) * res.nAlpha * res.nMu);
    t.diffuse.resize(size_t(res.nEta) * res.nAlpha);
    uint64_t sum = 0;
    in.read(reinterpret_cast<char*>(t.ext.data()), std::streamsize(t.ext.size() * sizeof(float)));
    in.read(reinterpret_cast<char*>(t.diffuse.data()), std::streamsize(t.diffuse.size() * sizeof(float)));
    in.read(reinterpret_cast<char*>(&sum), sizeof(sum));
    if (!in || in.peek() != std::char_traits<char>::eof()) {
        if (why) *why = "truncated or oversized";
        return std::nullopt;
    }
    const uint64_t expect = fnv1a(t.diffuse.data(), t.diffuse.size() * sizeof(float),
                                  fnv1a(t.ext.data(), t.ext.size() * sizeof(float)));
    if (sum != expect) {
        if (why) *why = "checksum mismatch";
        return std::nullopt;
    }
    for (const auto* table : {&t.ext, &t.diffuse})
        for (float v : *table)
            if (!(v >= 0.0f && v <= 1.0f)) {
                if (why) *why = "values out of range";
                return std::nullopt;
            }
    return t;
}

bool writeRoughTables(const std::string& path, const RoughTransmittanceTables& t) {
    namespace fs = std::filesystem;
    std::error_code ec;
    const fs::path p(path);
    if (p.has_parent_path()) fs::create_directories(p.parent_path(), ec);
    Header h{};
    std::memcpy(h.magic, kMagic, 8);
    h.version = kFormatVersion;
    h.type = uint32_t(t.type);
    h.nEta = t.res.nEta;
    h.nAlpha = t.res.nAlpha;
    h.nMu = t.res.nMu;
    h.quadrature = t.res.quadrature;
    h.etaMin = RoughTransmittanceTables::kEtaMin;
    h.etaMax = RoughTransmittanceTables::kEtaMax;
    h.alphaMax = RoughTransmittanceTables::kAlphaMax;
    const uint64_t sum = fnv1a(t.diffuse.data(), t.diffuse.size() * sizeof(float),
                               fnv1a(t.ext.data(), t.ext.size() * sizeof(float)));
    std::string bytes(reinterpret_cast<const char*>(&h), sizeof(h));
    bytes.append(reinterpret_cast<const char*>(t.ext.data()), t.ext.size() * sizeof(float));
    bytes.append(reinterpret_cast<const char*>(t.diffuse.data()), t.diffuse.size() * sizeof(float));
    bytes.append(reinterpret_cast<const char*>(&sum), sizeof(sum));
    // Atomic (core/io/atomic_file.h): a concurrent reader sees the old cache or the whole new one.
    try {
        writeFileAtomically(path, bytes);
    } catch (const Error&) {
        return false;
    }
    return true;
}

RoughTransmittanceTables loadOrBuildRoughTables(const std::string& path, MicrofacetType type,
                                                const RoughTableResolution& res) {
    std::string why;
    if (auto t = readRoughTables(path, type, res, &why)) return std::move(*t);
    if (why != "missing")
        std::cerr << "iris: warning: rough plastic table cache '" << path << "' is unusable (" << why
                  << "); rebuilding it\n";
    RoughTransmittanceTables t = buildRoughTables(type, res);
    if (!writeRoughTables(path, t))
        std::cerr << "iris: warning: could not write the rough plastic table cache '" << path << "'\n";
    return t;
}

std::string roughTablesCacheDir() {
    if (const char* d = std::getenv("IRIS_CACHE_DIR"); d && *d) return d;
    if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x) return std::string(x) + "/iris";
    if (const char* h = std::getenv("HOME"); h && *h) return std::string(h) + "/.cache/iris";
    return temporaryFolder() + "/iris-cache";  // a bad $TMPDIR: the cache write warns with this path
}

std::string roughTablesCachePath(MicrofacetType type, const RoughTableResolution& res) {
    return strCat(roughTablesCacheDir(), "/rough_plastic_", typeName(type), "_", res.nEta, "x", res.nAlpha, "x",
                  res.nMu, "_q", res.quadrature, "_v", kFormatVersion, ".bin");
}

namespace {
std::mutex gTablesMutex;
std::array<std::unique_ptr<const RoughTransmittanceTables>, 2> gTables;
std::array<std::atomic<int>, 2> gAcquired{};
}  // namespace

const RoughTransmittanceTables& roughPlasticTables(MicrofacetType type) {
    const int k = type == MicrofacetType::Beckmann ? 0 : 1;
    std::lock_guard<std::mutex> lock(gTablesMutex);
    if (!gTables[k]) {
        const RoughTableResolution res;
        gTables[k] = std::make_unique<const RoughTransmittanceTables>(
            loadOrBuildRoughTables(roughTablesCachePath(type, res), type, res));
        ++gAcquired[k];
    }
    return *gTables[k];
}

int roughPlasticTablesAcquired(MicrofacetType type) {
    return gAcquired[type == MicrofacetType::Beckmann ? 0 : 1].load();
}

}  // namespace iris
