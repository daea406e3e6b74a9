// Precomputed transmittances of a rough dielectric interface, for the rough plastic model
// (Jakob's "roughplastic"; thesis 000 §2.5, eqs. 2.37–2.54) and the thesis' proposed model (§3.2).
//
//   T(η, α, μ)  = ∫ f_t(ωi, ωt) |cosθt| dωt                          (eqs. 2.37/2.40 with the
//                 directional transmittance of a microfacet dielectric    cosine of the measure)
//                 (Walter et al. 2007 BTDF, Smith G = G1 G1, exact Λ) lit from the outside at
//                 cosθi = μ with relative index η = η_int/η_ext ≥ 1.
//   Td(η, α)    = (1/η²) · 2 ∫₀¹ T(η, α, μ) μ dμ                       (eqs. 2.39/2.43)
//                 the transmittance of the coat for uniform (Lambertian) light from INSIDE,
//                 obtained from the outside values by reciprocity (f_t/η_t² is symmetric).
//                 The coat's internal diffuse reflectance is Fdr = 1 − Td.
//
// Tables are computed by deterministic quadrature (Gauss-Legendre, split at the kinks of the
// integrand) in parallel (TBB), only when a material asks for them (roughPlasticTables(type)),
// once per distribution, and cached on disk (IRIS_CACHE_DIR, else $XDG_CACHE_HOME/iris, else
// ~/.cache/iris). They are read with Catmull-Rom cubic interpolation (eqs. 2.44–2.51).
// See docs/thesis_models.md for the resolution and the measured interpolation error.
#pragma once

#include <algorithm>
#include <optional>
#include <string>
#include <vector>

#include "materials/microfacet.h"
#include "spectral/lanes.h"

namespace iris {

struct RoughTableResolution {
    int nEta = 24, nAlpha = 32, nMu = 48;  // grid sizes (see docs/thesis_models.md)
    int quadrature = 16;                   // Gauss-Legendre points per dimension and piece
};

class RoughTransmittanceTables {
public:
    // Domain: η ∈ [1, 3] with nodes η_i = 1 + 2 (i/(nη−1))² (T varies like sqrt(η − 1) near
    // η = 1); α ∈ [0, 1] with nodes α_k = (k/(nα−1))²; μ ∈ [0, 1] uniform.
    static constexpr float kEtaMin = 1.0f, kEtaMax = 3.0f, kAlphaMax = 1.0f;

    MicrofacetType type = MicrofacetType::Beckmann;
    RoughTableResolution res;
    std::vector<float> ext;      // T(η, α, μ), index (iEta · nAlpha + iAlpha) · nMu + iMu
    std::vector<float> diffuse;  // Td(η, α), index iEta · nAlpha + iAlpha

    /// The (η, α) part of the tricubic stencil, collapsed: up to 16 μ-lines of the table with their
    /// weights. Lets a BSDF with fixed η, α look up T at several μ without recomputing it.
    struct Line {
        int offset[16];
        float weight[16];
        int count = 0;
    };
    Line line(float eta, float alpha) const;
    /// T at μ = cosTheta on a prepared line (Catmull-Rom in μ).
    float transmittance(const Line& l, float cosTheta) const;

    /// T(η, α, μ) by tricubic Catmull-Rom interpolation (eq. 2.44); arguments are clamped to
    /// the domain. T12 = transmittance(η, α, cosθi), T21 = transmittance(η, α, cosθo)
    /// (eqs. 2.52–2.53). Same as transmittance(line(η, α), μ).
    float transmittance(float eta, float alpha, float cosTheta) const { return transmittance(line(eta, alpha), cosTheta); }
    /// Td(η, α) by bicubic Catmull-Rom interpolation (eq. 2.51); Fdr = 1 − Td (eq. 2.54).
    float internalDiffuseTransmittance(float eta, float alpha) const;

    /// Grid node values (for tests).
    static float etaNode(int i, int n) { return kEtaMin + (kEtaMax - kEtaMin) * sqr(float(i) / float(n - 1)); }
    static float alphaNode(int i, int n) { return kAlphaMax * sqr(float(i) / float(n - 1)); }
    static float muNode(int i, int n) { return float(i) / float(n - 1); }
};

/// An interior η stencil (four consecutive η nodes) of a RoughTablesAtAlpha prepared for
/// RoughTablesAtAlpha::transmittances: the first of its four table rows and its four weights, each
/// broadcast to four lanes. row == nullptr: not interior (use the RoughStencil).
struct RoughEtaRows {
    lanes::Float4 w[4];
    const float* row = nullptr;
};

/// Catmull-Rom stencil (thesis eqs. 2.45–2.50): up to four (index, weight) pairs at grid
/// coordinate x ∈ [0, n−1]. Ghost nodes beyond the ends are linear extrapolations
/// (V₋₁ = 2V₀ − V₁, V_n = 2V_{n−1} − V_{n−2}), folded into the weights.
struct RoughStencil {
    int idx[4];
    float w[4];
    int count = 0;
};
inline void roughStencilAdd(RoughStencil& s, int i, float wt) {
    for (int k = 0; k < s.count; ++k)
        if (s.idx[k] == i) {
            s.w[k] += wt;
            return;
        }
    s.idx[s.count] = i;
    s.w[s.count++] = wt;
}

inline RoughStencil roughCatmullRom(float x, int n) {
    x = std::clamp(x, 0.0f, float(n - 1));
    const int i = std::min(int(x), n - 2);
    const float t = x - float(i), t2 = t * t, t3 = t2 * t;
    const float wts[4] = {-0.5f * t + t2 - 0.5f * t3,          // eq. 2.46
                          1.0f - 2.5f * t2 + 1.5f * t3,        // eq. 2.47
                          0.5f * t + 2.0f * t2 - 1.5f * t3,    // eq. 2.48
                          -0.5f * t2 + 0.5f * t3};             // eq. 2.49
    RoughStencil s;
    if (i >= 1 && i + 2 <= n - 1) {  // interior: four distinct nodes, no ghosts
        for (int k = 0; k < 4; ++k) {
            s.idx[k] = i - 1 + k;
            s.w[k] = wts[k];
        }
        s.count = 4;
        return s;
    }
    for (int k = 0; k < 4; ++k) {
        const int j = i - 1 + k;
        if (j < 0) {
            roughStencilAdd(s, 0, 2.0f * wts[k]);
            roughStencilAdd(s, 1, -wts[k]);
        } else if (j > n - 1) {
            roughStencilAdd(s, n - 1, 2.0f * wts[k]);
            roughStencilAdd(s, n - 2, -wts[k]);
        } else {
            roughStencilAdd(s, j, wts[k]);
        }
    }
    return s;
}

/// The tables at one fixed α, collapsed along α once. Eqs. 2.44 and 2.51 are linear in the table
/// values, so Σ_η Σ_α w_η w_α V[η, α, ·] = Σ_η w_η (Σ_α w_α V[η, α, ·]): per η node this keeps
/// one μ-line of T and one Td (exact up to float rounding). collapse() then folds the η stencil
/// too, giving the single μ-line of T(η, α, ·) that a BSDF with fixed (η, α) reads with a
/// 4-node Catmull-Rom in μ (instead of 16 lines × 4 nodes).
class RoughTablesAtAlpha {
public:
    RoughTablesAtAlpha() = default;
    RoughTablesAtAlpha(const RoughTransmittanceTables& t, float alpha);

    float alpha() const { return alpha_; }
    int nMu() const { return nMu_; }
    /// Writes the μ-line of T(η, α, ·) (nMu() values at the μ nodes, unclamped) to `line` and
    /// returns Td(η, α) (clamped to [0, 1] as internalDiffuseTransmittance). Deterministic: the
    /// same (η, this α) always gives bit-identical values.
    float collapse(float eta, float* line) const;

    /// The same without writing the line (for η that change per path, spectral mode): the η
    /// stencil, Td from it, and T at a μ stencil computing only the 4 line nodes it needs. Each
    /// performs the float operations of collapse() and roughLineTransmittance(), so
    /// transmittance(etaStencil(η), μ) == roughLineTransmittance(line of collapse(η), μ) exactly.
    RoughStencil etaStencil(float eta) const;
    /// etaStencil(eta[c]) and diffuse() of it for the n channels of one path (spectral mode, n ≤
    /// kMaxWavelengths), four channels at a time in SIMD lanes. Each lane performs the float
    /// operations of the scalar etaCoord / roughCatmullRom / diffuse in the same order (IEEE
    /// element-wise, no contraction), so se[c] == etaStencil(eta[c]) and td[c] == diffuse(se[c])
    /// bit for bit; a lane whose stencil is not interior (η at the ends of the table, NaN) and the
    /// n mod 4 last channels are computed by the scalar code. rows (optional): the interior
    /// stencils prepared for transmittances() instead; then se[c] is written only where
    /// rows[c].row == nullptr (the only se[c] transmittances() reads).
    void etaStencils(const float* eta, int n, RoughStencil* se, float* td, RoughEtaRows* rows = nullptr) const;
    float diffuse(const RoughStencil& se) const {
        float td = 0;
        for (int i = 0; i < se.count; ++i) td += se.w[i] * diffuse_[size_t(se.idx[i])];
        return std::clamp(td, 0.0f, 1.0f);  // eq. 2.51
    }
    /// Node m of the collapsed μ-line of se (line[m] of collapse()).
    float lineNode(const RoughStencil& se, int m) const {
        float v = 0.0f;
        for (int i = 0; i < se.count; ++i) v += se.w[i] * ext_[size_t(se.idx[i]) * size_t(nMu_) + size_t(m)];
        return v;
    }
    float transmittance(const RoughStencil& se, const RoughStencil& mu) const {
        float v = 0;
        if (se.count == 4 && mu.count == 4 && mu.idx[3] == mu.idx[0] + 3 && mu.idx[1] == mu.idx[0] + 1 &&
            mu.idx[2] == mu.idx[0] + 2) {
            // Interior stencils (the common case): the lineNode sums of the four consecutive μ
            // nodes side by side, same operations in the same order (0 + w0 r0 + w1 r1 + w2 r2 +
            // w3 r3 per node, then the μ sum).
            const size_t m0 = size_t(mu.idx[0]);
            const float* r0 = &ext_[size_t(se.idx[0]) * size_t(nMu_) + m0];
            const float* r1 = &ext_[size_t(se.idx[1]) * size_t(nMu_) + m0];
            const float* r2 = &ext_[size_t(se.idx[2]) * size_t(nMu_) + m0];
            const float* r3 = &ext_[size_t(se.idx[3]) * size_t(nMu_) + m0];
            // Lane k = node m0 + k (spectral/lanes.h: element-wise IEEE operations, the same
            // roundings as the scalar lineNode).
            const float* rows[4] = {r0, r1, r2, r3};
            lanes::Float4 node = lanes::broadcast(0.0f);
            for (int i = 0; i < 4; ++i) node = node + lanes::broadcast(se.w[i]) * lanes::load(rows[i]);
            for (int k = 0; k < 4; ++k) v += mu.w[k] * node[k];
        } else {
            for (int k = 0; k < mu.count; ++k) v += mu.w[k] * lineNode(se, mu.idx[k]);
        }
        return std::clamp(v, 0.0f, 1.0f);
    }

    /// transmittance(se[c], mu) for c = 0..n−1 into out[c]: the per-channel T of one path at one μ
    /// stencil (the μ stencil is shared by all channels). With consecutive μ nodes (every stencil
    /// of roughMuStencil: four interior nodes, or three at the ends of the μ range) and four
    /// channels with prepared interior rows (etaStencils), the four channels' sums run side by
    /// side: the node sums as in transmittance() (lane = μ node; the four loaded nodes are shifted
    /// back to stay inside the row at the upper end), then a 4×4 transpose and the μ sum with
    /// lane = channel, the same operations in the same order per channel, so out[c] ==
    /// transmittance(se[c], mu) exactly. Other channels take transmittance().
    __attribute__((always_inline)) void transmittances(const RoughStencil* se, const RoughEtaRows* rows, int n,
                                                       const RoughStencil& mu, float* out) const {
        int c = 0;
        bool consecutive = rows && nMu_ >= 4 && mu.count >= 1 && mu.count <= 4;
        for (int j = 1; consecutive && j < mu.count; ++j) consecutive = mu.idx[j] == mu.idx[0] + j;
        if (consecutive) {
            const int b = std::min(mu.idx[0], nMu_ - 4);  // first loaded node
            const int o = mu.idx[0] - b;                   // lane of the first stencil node
            const size_t stride = size_t(nMu_);
            using lanes::Float4;
            const Float4 zero = lanes::broadcast(0.0f), one = lanes::broadcast(1.0f);
            for (; c + 4 <= n; c += 4) {
                if (!rows[c].row || !rows[c + 1].row || !rows[c + 2].row || !rows[c + 3].row) {
                    for (int k = 0; k < 4; ++k) out[c + k] = channelTransmittance(se, rows, c + k, mu);
                    continue;
                }
                Float4 node[4];  // node[k][l]: channel c + k, μ node b + l (lineNode)
                for (int k = 0; k < 4; ++k) {
                    const RoughEtaRows& r = rows[c + k];
                    const float* p = r.row + b;
                    Float4 acc = zero;
                    for (int i = 0; i < 4; ++i) acc = acc + r.w[i] * lanes::load(p + size_t(i) * stride);
                    node[k] = acc;
                }
                Float4 v = zero;  // lane k = channel c + k
                for (int j = 0; j < mu.count; ++j) {
                    const int l = o + j;
                    const Float4 nj = {node[0][l], node[1][l], node[2][l], node[3][l]};
                    v = v + lanes::broadcast(mu.w[j]) * nj;
                }
                lanes::store(out + c, lanes::clamp(v, zero, one));  // std::clamp(v, 0, 1) per lane
            }
        }
        for (; c < n; ++c) out[c] = channelTransmittance(se, rows, c, mu);
    }
    /// T of channel c of transmittances(): from its prepared rows (the lineNode sums of
    /// transmittance(), same order) or from se[c].
    __attribute__((noinline)) float channelTransmittance(const RoughStencil* se, const RoughEtaRows* rows, int c,
                                                         const RoughStencil& mu) const {
        if (!rows || !rows[c].row) return transmittance(se[c], mu);
        const RoughEtaRows& r = rows[c];
        float v = 0;
        for (int k = 0; k < mu.count; ++k) {
            float node = 0.0f;
            for (int i = 0; i < 4; ++i) node += r.w[i][0] * r.row[size_t(i) * size_t(nMu_) + size_t(mu.idx[k])];
            v += mu.w[k] * node;
        }
        return std::clamp(v, 0.0f, 1.0f);
    }

private:
    float alpha_ = 0.0f;
    int nEta_ = 0, nMu_ = 0;
    std::vector<float> ext_;      // Σ_α w_α T[η_i, α, μ_m], index i · nMu + m
    std::vector<float> diffuse_;  // Σ_α w_α Td[η_i, α]
};

/// μ stencil of a direction with cosine cosTheta on lines of nMu nodes (clamped to [0, 1]).
inline RoughStencil roughMuStencil(float cosTheta, int nMu) {
    return roughCatmullRom(std::clamp(cosTheta, 0.0f, 1.0f) * float(nMu - 1), nMu);
}
/// T on a collapsed μ-line (eq. 2.44 after the collapse), clamped to [0, 1] as transmittance().
inline float roughLineTransmittance(const float* line, const RoughStencil& mu) {
    float v = 0;
    for (int k = 0; k < mu.count; ++k) v += mu.w[k] * line[mu.idx[k]];
    return std::clamp(v, 0.0f, 1.0f);
}

/// Brute-force directional transmittance T(η, α, μ) (double-precision quadrature with `q` points
/// per dimension and piece). η may be < 1 (light inside the denser medium; total internal
/// reflection then removes the corresponding microfacets). α = 0 gives the smooth 1 − F.
double roughTransmittanceIntegral(MicrofacetType type, double eta, double alpha, double mu, int q = 24);
/// Brute-force Td(η, α) = (1/η²) 2∫ T(η, α, μ) μ dμ (Gauss-Legendre in μ, `qMu` points).
double roughInternalDiffuseIntegral(MicrofacetType type, double eta, double alpha, int q = 24, int qMu = 32);

/// Brute-force directional reflectance R(η, α, μ) = ∫ f_r(ωi, ωo) cosθo dωo of the rough
/// interface (Walter et al. 2007 BRDF, Smith G = G1 G1, exact Λ) lit at cosθi = μ, same quadrature
/// as roughTransmittanceIntegral. η < 1: light inside the denser medium (facets beyond the
/// critical angle reflect totally). α = 0 gives the smooth F(μ). Single scattering: R + T < 1 for
/// α > 0 (the energy the rough interface loses).
double roughReflectanceIntegral(MicrofacetType type, double eta, double alpha, double mu, int q = 24);

/// Number of μ nodes of Mitsuba 3's roughplastic transmittance table (MI_ROUGH_TRANSMITTANCE_RES).
inline constexpr int kMitsuba3TransmittanceNodes = 64;
/// The internal reflectance Mitsuba 3's roughplastic divides the diffuse albedo by (1 − R_int):
/// R_int = 2 · (1/64) Σ_k R(1/η, α, μ_k) μ_k with μ_k = max(10⁻⁶, k/63), k = 0..63 (Mitsuba 3,
/// src/bsdfs/roughplastic.cpp, parameters_changed: the mean over its table's nodes, reproduced
/// here node for node; R by roughReflectanceIntegral with q points). Mitsuba 0.6 (and the thesis)
/// use Fdr = 1 − Td(η, α) instead, which also counts the interface's single-scattering loss as
/// reflected. q = 48 puts the quadrature error below 1e-4 (q = 24: 3e-4; measured against q = 96).
double mitsuba3InternalReflectance(MicrofacetType type, double eta, double alpha, int q = 48);

/// Mitsuba 3's R_int(η, α) (mitsuba3InternalReflectance) at one η for every α (a textured α),
/// tabulated at the α nodes of the tables (α_k = (k/(n−1))², computed in parallel) and read with
/// the tables' Catmull-Rom in sqrt α (thesis eqs. 2.45–2.49), clamped to [0, 1]. The nodes use
/// q = 24 (32 × 64 reflectance integrals, ~3e-4 from the converged values) to keep creation short.
class Mitsuba3InternalReflectanceCurve {
public:
    Mitsuba3InternalReflectanceCurve() = default;
    Mitsuba3InternalReflectanceCurve(MicrofacetType type, float eta, int nAlpha = RoughTableResolution{}.nAlpha,
                                     int q = 24);
    float at(float alpha) const;
    const std::vector<float>& nodes() const { return nodes_; }

private:
    std::vector<float> nodes_;
};

/// Compute all tables (parallel).
RoughTransmittanceTables buildRoughTables(MicrofacetType type, const RoughTableResolution& res);

/// Disk cache: read (returns nullopt and sets *why for a missing, truncated, corrupt or
/// mismatching file) and write (atomically: temporary file + rename; false on failure).
std::optional<RoughTransmittanceTables> readRoughTables(const std::string& path, MicrofacetType type,
                                                        const RoughTableResolution& res, std::string* why);
bool writeRoughTables(const std::string& path, const RoughTransmittanceTables& t);
/// Load from `path` or build (and write) them; a corrupt file gives a warning on stderr and a rebuild.
RoughTransmittanceTables loadOrBuildRoughTables(const std::string& path, MicrofacetType type,
                                                const RoughTableResolution& res);

/// Cache directory (IRIS_CACHE_DIR, else $XDG_CACHE_HOME/iris, else $HOME/.cache/iris) and the
/// file name keyed by the distribution, resolution, quadrature and format version.
std::string roughTablesCacheDir();
std::string roughTablesCachePath(MicrofacetType type, const RoughTableResolution& res);

/// The process-wide tables of a distribution: built or loaded on the first call (thread-safe),
/// then shared. Only rough-plastic-type materials call this.
const RoughTransmittanceTables& roughPlasticTables(MicrofacetType type);

/// How many times the process-wide tables were acquired (loaded or built), per distribution
/// (index 0 Beckmann, 1 GGX); for tests that check laziness.
int roughPlasticTablesAcquired(MicrofacetType type);

}  // namespace iris
