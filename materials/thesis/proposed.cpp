// The thesis' proposed model (thesis 000 §3.2, eqs. 3.15–3.30, Fig. 3.5): rough plastic energies
// (microfacet coat over a diffuse base, §2.5) evaluated per channel with that channel's η_t and λ,
// plus Granier & Heidrich's phase (interference) term.
//
// Per channel c (RGB: η_t[c], λ[c]; spectral: η_t(λ), λ), with η = η_t/η_i:
//   fr = ws · F D G / (4 μi μo)                                  (eq. 3.15)
//   ft = wd · T(η,α,μi) T(η,α,μo) / ((1 − Rd) π η²)              (eq. 3.16; Rd = Fdr = 1 − Td(η,α), eqs. 3.17–3.19)
//   Φ  = π η_t d/λ ((ωti + ωto)·(−n0)) = π η_t d/λ (cosθti + cosθto)   (eq. 3.20)
//   phase_mode "total" (the thesis):  f = fr + ft + 2 cos(2Φ) sqrt(fr ft)   (eqs. 3.21–3.22)
//   phase_mode "per_reflection" (thesis §5 future work): coherent sum over internal round trips,
//     amplitudes sqrt(fr) and sqrt(ft (1 − Rd)) Rd^(k/2), phase 2Φ per round trip:
//     f = |sqrt(fr) + sqrt(ft(1−Rd)) Σ_k Rd^(k/2) e^{i(k+1)2Φ}|²
//       = fr + ft(1−Rd)/D + 2 sqrt(fr ft (1−Rd)) (cos 2Φ − sqrt(Rd))/D,  D = 1 − 2 sqrt(Rd) cos 2Φ + Rd
//   phase = false: f = fr + ft (equals roughplastic with the same η, α, ws, wd; thesis §4.2.2).
// Sampling as rough plastic (eqs. 3.23–3.30): visible-normal reflection in the coat frame (normal
// n0) or a cosine lobe about n1, mixed with the probabilities of materials/thesis_rough_coat.h.
//
// Parameters (defaults: thesis Table 4.2):
//   n0, n1 (vector, (0,0,1)), eta_i (float|preset name, 1.0), eta_t (any IOR form, (1.8,1.7,1.6);
//   materials/thesis/thesis_channels.h), thickness (float|texture nm, 1000), wavelengths (rgb nm,
//   defaultChannelWavelengths()), alpha (float|texture, 0.08),
//   distribution (beckmann|ggx, beckmann), ws (0.6), wd (0.4), phase (bool, true),
//   phase_mode ("total"|"per_reflection", "total").
#include <cstddef>
#include <limits>
#include <optional>
#include <vector>

#include "core/registry.h"
#include "materials/material.h"
#include "materials/textures/texture_params.h"
#include "materials/thesis/thesis_channels.h"
#include "materials/thesis_rough_coat.h"

namespace iris {
namespace {

enum class PhaseMode { Off, Total, PerReflection };

class ProposedBSDF final : public BSDF {
public:
    /// Per-channel constants of one shading point.
    struct Channel {
        float eta;         // η_c = η_t,c/η_i
        float invEta2;     // (1/η_c)², the Snell factor of filmCosine
        float phaseScale;  // π η_t,c d/λ_c, the factor of (cosθti + cosθto) in eq. 3.20
        float ws, wdEff;   // ws and the effective diffuse weight wd/(1 − Rd) (eq. 3.16)
        float fdr;         // Rd = Fdr = 1 − Td(η_c, α) (eq. 3.19)
    };
    struct Params {
        RoughCoatChannels coatT;  // T(η_c, α, μ) per channel (collapsed lines or table stencils)
        MicrofacetDistribution dist;
        float d;
        Frame coat;        // frame of the top normal n0 (coat microfacet model)
        Frame base;        // frame of the base normal n1 (diffuse sampling)
        vec3 n1;
        bool tilted0, tilted1;
        PhaseMode phase;
        int n;             // channels (wavelengths) of the path
        const Channel* ch;
        float wsAvg, wdAvg;  // channel averages of ws and wd (sampling probability)
    };

    ProposedBSDF() = default;
    /// The parameters, filled in place by ProposedMaterial::getBSDF (no copy of Params).
    Params& params() { return p_; }

    vec3 toCoat(const vec3& w) const { return p_.tilted0 ? p_.coat.toLocal(w) : w; }

    SampledSpectrum eval(const vec3& wo, const vec3& wi, TransportMode) const override {
        const int n = p_.n;
        SampledSpectrum f(n);
        if (wo.z <= 0 || wi.z <= 0) return f;
        const WoTerms& o = woTerms(wo);
        const WiTerms& t = wiTerms(o, wi);
        const vec3 woC = o.woC, wiC = t.wiC;
        if (woC.z <= 0 || wiC.z <= 0) return f;
        const RoughCoatGeometry g = roughCoatGeometry(p_.dist, woC, wiC, o.g1o, t.half);
        float tI[kMaxWavelengths];  // T12 per channel (eq. 2.52); T21 is o.tO (eq. 2.53)
        p_.coatT.transmittance(wiC.z, n, tI);
        for (int c = 0; c < n; ++c) {
            const Channel& k = p_.ch[c];
            const float eta = k.eta;
            const float s = roughCoatSpecular(g, woC, eta);
            const float d = roughCoatDiffuse(tI[c], o.tO[c], eta);
            const float fr = k.ws * s;     // eq. 3.15
            const float ft = k.wdEff * d;  // eq. 3.16
            if (p_.phase == PhaseMode::Off) {
                f[c] = fr + ft;
                continue;
            }
            const float cosTi = filmCosine(k.invEta2, wiC.z);
            const float cosTo = o.cosTo[c];
            const float phi = k.phaseScale * (cosTi + cosTo);  // eq. 3.20
            const float cos2phi = std::cos(2.0f * phi);
            if (p_.phase == PhaseMode::Total) {
                f[c] = fr + ft + 2.0f * cos2phi * std::sqrt(fr * ft);  // eqs. 3.21–3.22
            } else {
                const float rd = k.fdr, r = std::sqrt(rd);
                const float a1sq = ft * (1.0f - rd);
                const float den = std::max(1e-12f, 1.0f - 2.0f * r * cos2phi + rd);
                f[c] = std::max(0.0f, fr + a1sq / den + 2.0f * std::sqrt(fr * a1sq) * (cos2phi - r) / den);
            }
        }
        return f;
    }

    std::optional<BSDFSample> sample(const vec3& wo, float uc, const vec2& u, TransportMode mode) const override {
        if (wo.z <= 0) return std::nullopt;
        const WoTerms& o = woTerms(wo);
        const vec3 woC = o.woC;
        if (woC.z <= 0) return std::nullopt;
        const float ps = o.ps;
        vec3 wi;
        uint32_t flags;
        if (uc < ps) {  // eqs. 3.23–3.25 (visible normals of the coat)
            const vec3 wiC = reflect(woC, p_.dist.sampleNormal(woC, u));
            wi = p_.tilted0 ? p_.coat.toWorld(wiC) : wiC;
            flags = kBSDFReflection | kBSDFGlossy;
        } else {  // eqs. 3.27–3.28 (cosine lobe about n1)
            const vec3 l = sampleCosineHemisphere(u);
            wi = p_.tilted1 ? p_.base.toWorld(l) : l;
            flags = kBSDFReflection | kBSDFDiffuse;
        }
        if (wi.z <= 0) return std::nullopt;
        return sampleFromEval(wo, wi, flags, mode);
    }

    /// Mixture density (eq. 3.30 with the selection probabilities): P p_spec + (1 − P) (wi·n1)/π.
    float pdf(const vec3& wo, const vec3& wi, TransportMode) const override {
        if (wo.z <= 0 || wi.z <= 0) return 0.0f;
        const WoTerms& o = woTerms(wo);
        if (o.woC.z <= 0) return 0.0f;
        const float ps = o.ps;
        const float cosB = p_.tilted1 ? glm::dot(wi, p_.n1) : wi.z;
        const WiTerms& t = wiTerms(o, wi);
        return ps * roughCoatSpecularPdf(o.woC, o.g1o, t.half) + (1.0f - ps) * cosineHemispherePdf(cosB);
    }

    uint32_t flags() const override { return kBSDFReflection | kBSDFGlossy | kBSDFDiffuse; }

private:
    /// What depends on wo alone. The integrator calls eval, pdf and sample of one shading point with
    /// the same wo (next-event estimation: eval + pdf; the BSDF sample: pdf + eval), so these are
    /// computed at the first call with a new wo and reused (pure functions of wo: the same values
    /// as recomputing them). A BSDF lives in one thread's Arena for one path sample
    /// (materials/material.h), so the mutable cache is never shared between threads.
    struct WoTerms {
        vec3 wo{std::numeric_limits<float>::quiet_NaN()};  // key (NaN: never equal, first call fills)
        // Filled by woTerms() before any read (left uninitialised: the BSDF is built per shading point).
        vec3 woC;   // wo in the coat frame
        float g1o;  // Smith G1 of woC without χ+: 1/(1 + Λ(woC))
        float ps;   // specular sampling probability (roughCoatSpecularProbability)
        float tO[kMaxWavelengths];     // T21 = T(η_c, α, cosθo) per channel (eq. 2.53)
        float cosTo[kMaxWavelengths];  // cosine of wo refracted into the film per channel (eq. 3.20)
    };

    /// What depends on the pair (wo, wi): wi in the coat frame, the half vector and D(h). eval and
    /// pdf of one pair follow each other (next-event estimation: eval then pdf; sample: pdf then
    /// eval), so the second call reuses them (pure functions of the pair: the same values).
    struct WiTerms {
        vec3 wo{std::numeric_limits<float>::quiet_NaN()}, wi{std::numeric_limits<float>::quiet_NaN()};  // key
        vec3 wiC;            // filled by wiTerms() before any read
        RoughCoatHalf half;  // of (woC, wiC)
    };

    const WiTerms& wiTerms(const WoTerms& o, const vec3& wi) const {
        WiTerms& t = wi_;
        if (wi == t.wi && o.wo == t.wo) return t;
        t.wo = o.wo;
        t.wi = wi;
        t.wiC = toCoat(wi);
        t.half = roughCoatHalf(p_.dist, o.woC, t.wiC);
        return t;
    }

    const WoTerms& woTerms(const vec3& wo) const {
        WoTerms& o = wo_;
        if (wo == o.wo) return o;
        o.wo = wo;
        o.woC = toCoat(wo);
        if (o.woC.z <= 0) return o;  // callers return zero / no sample
        const int n = p_.n;
        o.g1o = 1.0f / (1.0f + p_.dist.Lambda(o.woC));  // MicrofacetDistribution::smithG1's factor
        p_.coatT.transmittance(o.woC.z, n, o.tO);
        float t = 0.0f;
        for (int c = 0; c < n; ++c) t += o.tO[c];
        o.ps = roughCoatSpecularProbability(p_.wsAvg, p_.wdAvg, t / float(n));
        for (int c = 0; c < n; ++c) o.cosTo[c] = filmCosine(p_.ch[c].invEta2, o.woC.z);
        return o;
    }

    /// Cosine of a direction (cosine cosC about n0) refracted specularly into the film of relative
    /// index η (eqs. 3.1–3.2 reading; Snell's law: cos²θt = 1 − (1/η)² sin²θ), from invEta2 =
    /// (1/η)·(1/η) of the channel (the same float operations as computing 1/η here).
    static float filmCosine(float invEta2, float cosC) { return safeSqrt(1.0f - invEta2 * (1.0f - cosC * cosC)); }

    Params p_;
    mutable WoTerms wo_;
    mutable WiTerms wi_;
};

class ProposedMaterial final : public Material {
public:
    explicit ProposedMaterial(const Properties& p) {
        vec3 n0 = p.getVector("n0", vec3(0, 0, 1)), n1 = p.getVector("n1", vec3(0, 0, 1));
        if (!(glm::length(n0) > 0) || !(glm::length(n1) > 0)) failAt(p.location(), "proposed: n0 and n1 must be non-zero");
        n0 = glm::normalize(n0);
        n1_ = glm::normalize(n1);
        if (n0.z <= 0 || n1_.z <= 0) failAt(p.location(), "proposed: n0 and n1 must point into the upper hemisphere (z > 0)");
        tilted0_ = !(n0.x == 0 && n0.y == 0);
        tilted1_ = !(n1_.x == 0 && n1_.y == 0);
        coat_ = Frame::fromNormal(n0);
        base_ = Frame::fromNormal(n1_);
        etaI_ = readConstantIOR(p, "eta_i", 1.0f);
        channels_ = ThesisChannels::read(p, "proposed", vec3(1.8f, 1.7f, 1.6f));
        const IOR::Range etaT = channels_.etaT.range();
        const float lo = etaT.min / etaI_, hi = etaT.max / etaI_;
        if (lo < RoughTransmittanceTables::kEtaMin || hi > RoughTransmittanceTables::kEtaMax)
            failAt(p.location(), "proposed: eta_t/eta_i must lie in the tabulated range [", RoughTransmittanceTables::kEtaMin,
                   ", ", RoughTransmittanceTables::kEtaMax, "], got [", lo, ", ", hi, "]");
        thickness_ = getFloatTexture(p, "thickness", 1000.0f);
        if (thickness_->isConstant() && !(thickness_->eval({}) >= 0))
            failAt(p.locationOf("thickness"), "proposed: thickness must be >= 0 nm, got ", thickness_->eval({}));
        alpha_ = getFloatTexture(p, "alpha", 0.08f);
        if (const auto* c = dynamic_cast<const ConstantFloatTexture*>(alpha_.get());
            c && !(c->value() >= 0 && c->value() <= RoughTransmittanceTables::kAlphaMax))
            failAt(p.locationOf("alpha"), "proposed: alpha must be in [0, 1], got ", c->value());
        type_ = withLocation(p.locationOf("distribution"), [&] { return MicrofacetDistribution::parseType(p.getString("distribution", "beckmann")); }, "proposed: ");
        ws_ = getSpectrumTexture(p, "ws", SpectrumKind::Reflectance, 0.6f);
        wd_ = getSpectrumTexture(p, "wd", SpectrumKind::Reflectance, 0.4f);
        // Weights that are one number at every point and wavelength (the thesis' ws, wd): read
        // them once here instead of evaluating the textures per shading point (the same values:
        // ConstantSpectrum::sample fills every entry with its value).
        constWeights_ = constantValue(*ws_, &wsConst_) && constantValue(*wd_, &wdConst_);
        const bool phase = p.getBool("phase", true);
        const std::string mode = p.getString("phase_mode", "total");
        if (mode != "total" && mode != "per_reflection")
            failAt(p.locationOf("phase_mode"), "proposed: phase_mode must be 'total' or 'per_reflection', got '", mode, "'");
        phase_ = !phase ? PhaseMode::Off : mode == "total" ? PhaseMode::Total : PhaseMode::PerReflection;
        tables_ = &roughPlasticTables(type_);
        // Constant α (the thesis setting): collapse the tables along α once, and in RGB mode (fixed
        // η per channel) fold the η stencil too: one μ-line and one Fdr per channel, shared by all
        // shading points (RoughTablesAtAlpha; exact up to float rounding).
        if (const auto* c = dynamic_cast<const ConstantFloatTexture*>(alpha_.get())) {
            atAlpha_.emplace(*tables_, std::clamp(c->value(), 0.0f, RoughTransmittanceTables::kAlphaMax));
            const int nMu = atAlpha_->nMu();
            rgbLines_.assign(size_t(3) * nMu, 0.0f);
            const SampledSpectrum rgbEtaT = channels_.etaT.sample(channels_.rgb);
            for (int k = 0; k < 3; ++k)
                rgbFdr_[k] = 1.0f - atAlpha_->collapse(rgbEtaT[k] / etaI_, &rgbLines_[size_t(k) * nMu]);  // eq. 3.19
        }
    }

    const BSDF* getBSDF(const ShadingPoint& sp, SampledWavelengths& wl, Arena& arena) const override {
        const int n = wl.size();
        ProposedBSDF* bsdf = arena.make<ProposedBSDF>();
        ProposedBSDF::Params& q = bsdf->params();
        const float alpha = std::clamp(alpha_->eval(sp.tex), 0.0f, RoughTransmittanceTables::kAlphaMax);
        q.dist = MicrofacetDistribution(type_, alpha, alpha);
        q.d = std::max(0.0f, thickness_->eval(sp.tex));
        q.coat = coat_;
        q.base = base_;
        q.n1 = n1_;
        q.tilted0 = tilted0_;
        q.tilted1 = tilted1_;
        q.phase = phase_;
        q.n = n;
        SampledSpectrum ws, wd;  // unused with constWeights_
        if (!constWeights_) {
            ws = ws_->eval(sp.tex, wl);
            wd = wd_->eval(sp.tex, wl);
        }
        // Per-channel arrays in the arena (typed): the channels, and (spectral, constant α) the η
        // stencils and their prepared rows.
        const bool spectralStencils = atAlpha_ && !(wl.isRGB() && n == 3);
        ProposedBSDF::Channel* ch = arena.makeArray<ProposedBSDF::Channel>(size_t(n));
        float eta[kMaxWavelengths], wdC[kMaxWavelengths];
        float wsSum = 0.0f, wdSum = 0.0f;  // in channel order, as SampledSpectrum::average
        const SampledWavelengths& cw = channels_.of(wl);  // the wavelengths the channels stand for
        for (int c = 0; c < n; ++c) {
            const float etaT = channels_.etaT.at(cw, c), lambda = cw.lambda(c);  // η_t and λ of the channel
            eta[c] = etaT / etaI_;
            const float inv = 1.0f / eta[c];
            ch[c].eta = eta[c];
            ch[c].invEta2 = inv * inv;
            ch[c].phaseScale = kPi * etaT * q.d / lambda;  // eq. 3.20 without the cosines
            ch[c].ws = std::max(0.0f, constWeights_ ? wsConst_ : ws[c]);  // clampZero
            wdC[c] = std::max(0.0f, constWeights_ ? wdConst_ : wd[c]);
            wsSum += ch[c].ws;
            wdSum += wdC[c];
        }
        q.wsAvg = n > 0 ? wsSum / float(n) : 0.0f;
        q.wdAvg = n > 0 ? wdSum / float(n) : 0.0f;
        q.coatT.tables = tables_;
        if (atAlpha_) {
            const int nMu = atAlpha_->nMu();
            q.coatT.nMu = nMu;
            if (!spectralStencils) {  // RGB mode: the per-material lines of the three fixed channel η
                q.coatT.lines = rgbLines_.data();
                for (int c = 0; c < n; ++c) {
                    ch[c].fdr = rgbFdr_[c];
                    ch[c].wdEff = roughCoatAlbedo(wdC[c], ch[c].fdr, false);  // wd/(1 − Rd)
                }
            } else {  // spectral: η(λ) varies per path; one η stencil per channel on the α-collapsed tables
                RoughStencil* se = arena.makeArray<RoughStencil>(size_t(n));
                RoughEtaRows* rows = arena.makeArray<RoughEtaRows>(size_t(n));
                float td[kMaxWavelengths];
                atAlpha_->etaStencils(eta, n, se, td, rows);  // = etaStencil(η_c), diffuse(·) per channel
                for (int c = 0; c < n; ++c) {
                    ch[c].fdr = 1.0f - td[c];                                    // eq. 3.19
                    ch[c].wdEff = roughCoatAlbedo(wdC[c], ch[c].fdr, false);  // wd/(1 − Rd)
                }
                q.coatT.atAlpha = &*atAlpha_;
                q.coatT.etaStencils = se;
                q.coatT.etaRows = rows;
            }
        } else {  // textured α: the (η, α) stencils of the full tables
            using Line = RoughTransmittanceTables::Line;
            Line* lines = arena.makeArray<Line>(size_t(n));
            for (int c = 0; c < n; ++c) {
                lines[c] = tables_->line(eta[c], alpha);
                ch[c].fdr = 1.0f - tables_->internalDiffuseTransmittance(eta[c], alpha);  // eq. 3.19
                ch[c].wdEff = roughCoatAlbedo(wdC[c], ch[c].fdr, false);                  // wd/(1 − Rd)
            }
            q.coatT.stencils = lines;
        }
        q.ch = ch;
        return bsdf;
    }

private:
    /// The value of a texture that is a ConstantSpectrum everywhere.
    static bool constantValue(const SpectrumTexture& t, float* v) {
        const auto* c = dynamic_cast<const ConstantSpectrum*>(t.constantSpectrum());
        if (c) *v = c->value();
        return c != nullptr;
    }

    Frame coat_, base_;
    vec3 n1_;
    bool tilted0_, tilted1_;
    float etaI_;
    ThesisChannels channels_;
    FloatTexturePtr thickness_, alpha_;
    MicrofacetType type_;
    SpectrumTexturePtr ws_, wd_;
    bool constWeights_ = false;  // ws and wd are ConstantSpectrum values: wsConst_, wdConst_
    float wsConst_ = 0.0f, wdConst_ = 0.0f;
    PhaseMode phase_;
    const RoughTransmittanceTables* tables_;
    std::optional<RoughTablesAtAlpha> atAlpha_;  // constant α only
    std::vector<float> rgbLines_;                // RGB mode: channel k's μ-line at k · nMu
    float rgbFdr_[3] = {0, 0, 0};
};

std::shared_ptr<Material> createProposed(const Properties& p) { return std::make_shared<ProposedMaterial>(p); }

}  // namespace

IRIS_REGISTER(MaterialRegistry, "proposed", createProposed);

}  // namespace iris
