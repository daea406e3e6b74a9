// Rough plastic (Jakob; Mitsuba "roughplastic"; thesis 000 §2.5, eqs. 2.36–2.56): a rough
// dielectric coat (Walter et al. 2007 microfacet reflection) over a Lambertian base, with the
// coat's transmittances read from precomputed tables (materials/rough_plastic_tables.h).
// Model and readings: materials/thesis_rough_coat.h and docs/thesis_models.md.
//
// Parameters (Mitsuba names):
//   distribution          "beckmann" | "ggx"                       default beckmann
//   alpha                 float | texture, roughness in [0, 1]     default 0.1
//   int_ior, ext_ior      float | preset name, η = int/ext ∈ [1, 3]  default 1.49, 1.000277
//   diffuse_reflectance   spectrum | texture (base albedo ρ)       default 0.5
//   specular_reflectance  spectrum | texture (ks)                  default 1.0
//   nonlinear             bool (ρ/(1−ρFdr) instead of ρ/(1−Fdr))   default false
//   sample_visible        bool, visible-normal sampling              default true
//
//   convention            "mitsuba3" | "mitsuba0.6" (below)         default "mitsuba3"
//
// `convention` chooses the internal reflectance Fdr of the coat (core/mitsuba_convention.h; the
// upgrade pass gives a version 0.x file's "mitsuba0.6"; docs/scene_format.md):
//   "mitsuba0.6" (Mitsuba 0.6, the thesis): Fdr = 1 − Td(η, α) (eq. 2.54), tabulated;
//   "mitsuba3": Fdr = R_int = 2∫ R(1/η, α, μ) μ dμ, the rough interface's own
//   directional reflectance from inside, as Mitsuba 3's mean over 64 nodes
//   (mitsuba3InternalReflectance). It is smaller than 1 − Td by the interface's single-scattering
//   loss, so the base looks darker (1/(1 − Fdr) 2 % lower at α = 0.01, 64 % at α = 1; GGX, η 1.5).
// Everything else (specular lobe, T12 T21 / η², sampling) is the same model in both.
#include "core/registry.h"
#include "materials/fresnel_mueller.h"
#include "materials/material.h"
#include "materials/textures/texture_params.h"
#include "materials/thesis_rough_coat.h"
#include "spectral/ior_params.h"

namespace iris {
namespace {

class RoughPlasticBSDF final : public BSDF {
public:
    /// `line`: the collapsed μ-line of (η, α) (nMu values), or nullptr to read the full tables
    /// through the (η, α) stencil (textured α). `fdr`: the coat's internal reflectance (see top).
    RoughPlasticBSDF(const RoughTransmittanceTables* t, const float* line, float fdr, MicrofacetDistribution dist,
                     float alpha, float eta, const SampledSpectrum& ks, const SampledSpectrum& rho, bool nonlinear)
        : dist_(dist), eta_(eta), ks_(ks), rhoEff_(rho), rhoAvg_(rho.average()) {
        coatT_.tables = t;
        if (line) {
            coatT_.lines = line;
            coatT_.nMu = t->res.nMu;
        } else {
            stencil_ = t->line(eta, alpha);
            coatT_.stencils = &stencil_;
        }
        for (int c = 0; c < rho.size(); ++c) rhoEff_[c] = roughCoatAlbedo(rho[c], fdr, nonlinear);
    }

    RoughPlasticBSDF(const RoughPlasticBSDF&) = delete;  // coatT_ may point at stencil_
    RoughPlasticBSDF& operator=(const RoughPlasticBSDF&) = delete;

    float transmittance(float cosTheta) const {
        float t;
        coatT_.transmittance(cosTheta, 1, &t);
        return t;
    }

    SampledSpectrum eval(const vec3& wo, const vec3& wi, TransportMode) const override {
        SampledSpectrum f(ks_.size());
        if (wo.z <= 0 || wi.z <= 0) return f;
        const float s = roughCoatSpecular(roughCoatGeometry(dist_, wo, wi), wo, eta_);  // eq. 2.36
        const float d = roughCoatDiffuse(transmittance(wi.z), transmittance(wo.z), eta_);  // eq. 2.55
        for (int c = 0; c < f.size(); ++c) f[c] = ks_[c] * s + rhoEff_[c] * d;   // eq. 2.56
        return f;
    }

    /// Polarized: the specular lobe is the microfacet's Fresnel reflection matrix (the pattern of
    /// Mitsuba 3 roughconductor.cpp and pplastic.cpp), the diffuse lobe a depolarizer (Mitsuba 3's
    /// roughplastic depolarizes both; docs/polarization.md).
    MuellerSpectrum evalMueller(const vec3& wo, const vec3& wi, TransportMode mode) const override {
        const int n = ks_.size();
        if (wo.z <= 0 || wi.z <= 0) return MuellerSpectrum::depolarizer(SampledSpectrum(n));
        const float d = roughCoatDiffuse(transmittance(wi.z), transmittance(wo.z), eta_);
        MuellerSpectrum M = MuellerSpectrum::depolarizer(rhoEff_ * d);
        const RoughCoatGeometry g = roughCoatGeometry(dist_, wo, wi);
        if (g.dg > 0) M += fresnelReflectionMueller(g.h, wi, wo, SampledSpectrum(n, eta_)) * (ks_ * g.dg);
        return M;
    }
    std::optional<PolarizedBSDFSample> sampleMueller(const vec3& wo, float uc, const vec2& u, TransportMode mode) const override {
        return withEvalMueller(*this, sample(wo, uc, u, mode), wo, mode);
    }

    float specularProbability(const vec3& wo) const {
        return roughCoatSpecularProbability(ks_.average(), rhoAvg_, transmittance(wo.z));
    }

    std::optional<BSDFSample> sample(const vec3& wo, float uc, const vec2& u, TransportMode mode) const override {
        if (wo.z <= 0) return std::nullopt;
        const float ps = specularProbability(wo);
        vec3 wi;
        uint32_t flags;
        if (uc < ps) {
            const vec3 m = dist_.sampleNormal(wo, u);
            wi = reflect(wo, m);
            flags = kBSDFReflection | kBSDFGlossy;
        } else {
            wi = sampleCosineHemisphere(u);
            flags = kBSDFReflection | kBSDFDiffuse;
        }
        if (wi.z <= 0) return std::nullopt;
        return sampleFromEval(wo, wi, flags, mode);
    }

    float pdf(const vec3& wo, const vec3& wi, TransportMode) const override {
        if (wo.z <= 0 || wi.z <= 0) return 0.0f;
        const float ps = specularProbability(wo);
        return ps * roughCoatSpecularPdf(dist_, wo, wi) + (1.0f - ps) * cosineHemispherePdf(wi.z);
    }

    uint32_t flags() const override { return kBSDFReflection | kBSDFGlossy | kBSDFDiffuse; }

private:
    RoughCoatChannels coatT_;                  // one channel: T(η, α, μ)
    RoughTransmittanceTables::Line stencil_;  // textured α: table stencil of (η, α)
    MicrofacetDistribution dist_;
    float eta_;
    SampledSpectrum ks_, rhoEff_;
    float rhoAvg_;
};

class RoughPlasticMaterial final : public Material {
public:
    explicit RoughPlasticMaterial(const Properties& p) {
        type_ = withLocation(p.locationOf("distribution"), [&] { return MicrofacetDistribution::parseType(p.getString("distribution", "beckmann")); }, "roughplastic: ");
        alpha_ = getFloatTexture(p, "alpha", 0.1f);
        // Mitsuba 3's defaults "polypropylene" and "air"; a float or a preset name (spectral/ior_params.h).
        const float intIor = readConstantIOR(p, "int_ior", 1.49f), extIor = readConstantIOR(p, "ext_ior", 1.000277f);
        eta_ = intIor / extIor;
        if (eta_ < RoughTransmittanceTables::kEtaMin || eta_ > RoughTransmittanceTables::kEtaMax)
            failAt(p.location(), "roughplastic: int_ior/ext_ior = ", eta_, " is outside the tabulated range [",
                   RoughTransmittanceTables::kEtaMin, ", ", RoughTransmittanceTables::kEtaMax, "]");
        if (const auto* c = dynamic_cast<const ConstantFloatTexture*>(alpha_.get());
            c && !(c->value() >= 0 && c->value() <= RoughTransmittanceTables::kAlphaMax))
            failAt(p.locationOf("alpha"), "roughplastic: alpha must be in [0, 1], got ", c->value());
        rho_ = getSpectrumTexture(p, "diffuse_reflectance", SpectrumKind::Reflectance, 0.5f);
        ks_ = getSpectrumTexture(p, "specular_reflectance", SpectrumKind::Reflectance, 1.0f);
        nonlinear_ = p.getBool("nonlinear", false);
        sampleVisible_ = p.getBool("sample_visible", true);  // Mitsuba 0.6 and 3: true
        mitsuba3_ = getConvention(p) == MitsubaConvention::Mitsuba3;
        tables_ = &roughPlasticTables(type_);  // first use builds or loads them
        // Constant α: the (η, α) stencil collapsed once into one μ-line (RoughTablesAtAlpha).
        if (const auto* c = dynamic_cast<const ConstantFloatTexture*>(alpha_.get())) {
            const float alpha = std::clamp(c->value(), 0.0f, RoughTransmittanceTables::kAlphaMax);
            const RoughTablesAtAlpha atAlpha(*tables_, alpha);
            line_.assign(size_t(atAlpha.nMu()), 0.0f);
            lineFdr_ = 1.0f - atAlpha.collapse(eta_, line_.data());  // eq. 2.54
            // Mitsuba 3 clamps α to 10⁻⁴ (MicrofacetDistribution::configure).
            if (mitsuba3_) lineFdr_ = float(mitsuba3InternalReflectance(type_, eta_, std::max(alpha, 1e-4f)));
        } else if (mitsuba3_) {
            // Textured α (an iris extension; Mitsuba 3 takes a float): R_int over α at this η.
            rIntCurve_ = Mitsuba3InternalReflectanceCurve(type_, eta_);
        }
    }

    /// The coat's internal reflectance at a textured α (see the top of the file).
    float textureFdr(float alpha) const {
        if (mitsuba3_) return rIntCurve_.at(alpha);
        return 1.0f - tables_->internalDiffuseTransmittance(eta_, alpha);  // eq. 2.54
    }

    const BSDF* getBSDF(const ShadingPoint& sp, SampledWavelengths& wl, Arena& arena) const override {
        const float alpha = std::clamp(alpha_->eval(sp.tex), 0.0f, RoughTransmittanceTables::kAlphaMax);
        const bool constant = !line_.empty();
        return arena.make<RoughPlasticBSDF>(tables_, constant ? line_.data() : nullptr,
                                            constant ? lineFdr_ : textureFdr(alpha),
                                            MicrofacetDistribution(type_, alpha, alpha, sampleVisible_), alpha, eta_,
                                            clampZero(ks_->eval(sp.tex, wl)), clampZero(rho_->eval(sp.tex, wl)),
                                            nonlinear_);
    }

private:
    MicrofacetType type_;
    FloatTexturePtr alpha_;
    float eta_;
    SpectrumTexturePtr rho_, ks_;
    bool nonlinear_, sampleVisible_, mitsuba3_;
    const RoughTransmittanceTables* tables_;
    std::vector<float> line_;  // constant α: collapsed μ-line of (η, α)
    float lineFdr_ = 0.0f;     // constant α: the coat's internal reflectance
    Mitsuba3InternalReflectanceCurve rIntCurve_;  // textured α, convention mitsuba3
};

std::shared_ptr<Material> createRoughPlastic(const Properties& p) { return std::make_shared<RoughPlasticMaterial>(p); }

}  // namespace

IRIS_REGISTER(MaterialRegistry, "roughplastic", createRoughPlastic);

}  // namespace iris
