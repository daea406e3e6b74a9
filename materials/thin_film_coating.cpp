// Thin-film coating parameters and their per-path evaluation (see film_coating.h).
#include "materials/thin_film_coating.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "core/quadrature.h"
#include "materials/textures/texture_params.h"
#include "spectral/belcour_barla.h"
#include "spectral/thin_film_cycles.h"
#include "spectral/conductor_presets.h"
#include "spectral/thin_film_airy.h"
#include "spectral/thin_film_airy_batch.h"
#include "spectral/ior_params.h"

namespace iris {

// ---- ThinFilmCoatingSpec ----

namespace {

IOR readExtinction(const Properties& p, const std::string& name, float def) {
    return readIOR(p, name, IOR::constant(def), IorQuantity::Extinction);
}

}  // namespace

ThinFilmCoatingSpec ThinFilmCoatingSpec::fromProperties(const Properties& p, float defSubstrateEta, float defSubstrateK,
                                                float defThickness, const char* etaName, const char* kName) {
    ThinFilmCoatingSpec s;
    s.extIor = readConstantIOR(p, "ext_ior", 1.0f);
    s.filmIor = readIOR(p, "film_ior", IOR::constant(1.5f));
    s.filmK = readExtinction(p, "film_k", 0.0f);
    s.thickness = getFloatTexture(p, "thickness", defThickness);
    if (s.thickness->isConstant() && s.thickness->eval({}) < 0)
        failAt(p.locationOf("thickness"), "thickness must be >= 0 nm, got ", s.thickness->eval({}));
    for (int i = 1; i <= 8; ++i) {
        const std::string base = "layer" + std::to_string(i);
        if (!iorGiven(p, base + "_ior")) {
            if (p.has(base + "_thickness") || p.has(base + "_k"))
                failAt(p.location(), base, "_ior is required when ", base, "_thickness or ", base, "_k is given");
            break;
        }
        ExtraLayer l;
        l.ior = readIOR(p, base + "_ior", IOR::constant(1.5f));
        l.k = readExtinction(p, base + "_k", 0.0f);
        l.thicknessNm = p.getFloat(base + "_thickness");
        if (!(l.thicknessNm >= 0)) failAt(p.locationOf(base + "_thickness"), base, "_thickness must be >= 0 nm");
        s.extra.push_back(l);
    }
    s.substrateEta = readIOR(p, etaName, IOR::constant(defSubstrateEta));
    if (kName && p.has("substrate_material")) {
        if (p.has(etaName) || p.has(kName))
            failAt(p.locationOf("substrate_material"), "give either substrate_material or ", etaName, "/", kName, ", not both");
        const std::string name = p.getString("substrate_material");
        const ConductorSpectra c = withLocation(p.locationOf("substrate_material"), [&] { return loadConductorPreset(name); });
        if (c.mirror()) failAt(p.locationOf("substrate_material"), "substrate_material 'none' (perfect mirror) has no index");
        s.substrateEta = IOR::tabulated(c.eta);
        s.substrateK = IOR::tabulated(c.k);
    } else if (kName) {
        s.substrateK = readExtinction(p, kName, defSubstrateK);
    } else {
        s.substrateK = IOR::constant(0.0f);
    }

    const std::string mode = p.getString("phase_mode", "exact");
    if (mode == "exact") s.mode = ThinFilmPhaseMode::Exact;
    else if (mode == "incoherent") s.mode = ThinFilmPhaseMode::Incoherent;
    else if (mode == "truncated") s.mode = ThinFilmPhaseMode::Truncated;
    else failAt(p.locationOf("phase_mode"), "phase_mode must be 'exact', 'incoherent' or 'truncated', got '", mode, "'");
    s.bounces = p.getInt("bounces", 1);
    if (s.bounces < 0) failAt(p.locationOf("bounces"), "bounces must be >= 0, got ", s.bounces);
    if (s.mode != ThinFilmPhaseMode::Exact && !s.extra.empty())
        failAt(p.locationOf("phase_mode"), "phase_mode '", mode, "' applies to a single film; extra layers need 'exact'");

    const std::string rgb = p.getString("rgb_mode", "point");
    if (rgb == "point") s.rgbMode = ThinFilmRGBMode::Point;
    else if (rgb == "belcour_barla") s.rgbMode = ThinFilmRGBMode::BelcourBarla;
    else if (rgb == "cycles_4_2") s.rgbMode = ThinFilmRGBMode::Cycles42;
    else failAt(p.locationOf("rgb_mode"), "rgb_mode must be 'point', 'belcour_barla' or 'cycles_4_2', got '", rgb, "'");
    if (s.rgbMode != ThinFilmRGBMode::Point) {
        const SourceLocation loc = p.locationOf("rgb_mode");
        if (!s.extra.empty()) failAt(loc, "rgb_mode '", rgb, "' supports a single film only");
        if (s.mode != ThinFilmPhaseMode::Exact)
            failAt(loc, "rgb_mode '", rgb, "' integrates the exact Airy sum; use phase_mode 'exact'");
        for (float l = kLambdaMin; l <= kLambdaMax; l += 5.0f)
            if (s.filmK.eval(l) != 0)
                failAt(p.locationOf("film_k"), "rgb_mode '", rgb, "' needs a non-absorbing film (film_k = 0)");
    }
    if (s.rgbMode == ThinFilmRGBMode::Cycles42)  // Cycles 4.2 applies the film to dielectric bases only
        for (float l = kLambdaMin; l <= kLambdaMax; l += 5.0f)
            if (s.substrateK.eval(l) != 0)
                failAt(p.locationOf("rgb_mode"), "rgb_mode 'cycles_4_2' needs a dielectric substrate (extinction 0): "
                       "Cycles 4.2 has no thin film on metals");
    return s;
}

// ---- ThinFilmCoating ----

namespace {
/// Textured thickness: negative, NaN or infinite values (e.g. from a bitmap) become 0 nm.
double sanitizeThickness(float t) { return std::isfinite(t) ? std::max(0.0f, t) : 0.0; }
}  // namespace

ThinFilmCoating::ThinFilmCoating(const ThinFilmCoatingSpec& spec, const TextureQuery& q, const SampledWavelengths& wl, Arena& arena)
    : n_(wl.size()),
      nExtra_(int(spec.extra.size())),
      bounces_(spec.bounces),
      mode_(spec.mode),
      belcourBarla_(wl.isRGB() && spec.rgbMode == ThinFilmRGBMode::BelcourBarla),
      cycles42_(wl.isRGB() && spec.rgbMode == ThinFilmRGBMode::Cycles42),
      extIor_(spec.extIor),
      thickness_(sanitizeThickness(spec.thickness->eval(q))) {
    rgb_ = wl.isRGB();
    if (spec.rintCache) {
        const vec3& l = spec.rintCache->rgbLambdas;
        if (!rgb_ || (wl.lambda(0) == l[0] && wl.lambda(1) == l[1] && wl.lambda(2) == l[2])) rint_ = spec.rintCache.get();
    }
    // Every index spectrum sampled once for all wavelengths (IOR::sample is per spectrum, not per entry).
    const SampledSpectrum filmN = spec.filmIor.sample(wl), filmK = spec.filmK.sample(wl);
    const SampledSpectrum subN = spec.substrateEta.sample(wl), subK = spec.substrateK.sample(wl);
    SampledSpectrum* extra = nullptr;  // layer j: extra[2j] index, extra[2j + 1] extinction
    if (nExtra_ > 0) {
        extra = static_cast<SampledSpectrum*>(arena.allocate(sizeof(SampledSpectrum) * 2 * nExtra_, alignof(SampledSpectrum)));
        for (int j = 0; j < nExtra_; ++j) {
            new (extra + 2 * j) SampledSpectrum(spec.extra[j].ior.sample(wl));
            new (extra + 2 * j + 1) SampledSpectrum(spec.extra[j].k.sample(wl));
        }
    }
    for (int k = 0; k < n_; ++k) {
        lambda_[k] = wl.lambda(k);
        film_[k] = complexd(filmN[k], filmK[k]);
        substrate_[k] = complexd(subN[k], subK[k]);
    }
    init(spec, arena, [&](int j, int k) { return complexd(extra[2 * j][k], extra[2 * j + 1][k]); });
}

ThinFilmCoating::ThinFilmCoating(const ThinFilmCoatingSpec& spec, const TextureQuery& q, const float* lambdas, int n, Arena& arena)
    : n_(n),
      nExtra_(int(spec.extra.size())),
      bounces_(spec.bounces),
      mode_(spec.mode),
      extIor_(spec.extIor),
      thickness_(sanitizeThickness(spec.thickness->eval(q))) {
    for (int k = 0; k < n_; ++k) {
        lambda_[k] = lambdas[k];
        film_[k] = complexd(spec.filmIor.eval(lambdas[k]), spec.filmK.eval(lambdas[k]));
        substrate_[k] = complexd(spec.substrateEta.eval(lambdas[k]), spec.substrateK.eval(lambdas[k]));
    }
    init(spec, arena, [&](int j, int k) { return complexd(spec.extra[j].ior.eval(lambdas[k]), spec.extra[j].k.eval(lambdas[k])); });
}

template <typename ExtraIorAt>
void ThinFilmCoating::init(const ThinFilmCoatingSpec& spec, Arena& arena, ExtraIorAt&& extraIor) {
    if (mode_ == ThinFilmPhaseMode::Exact && nExtra_ == 0) {
        // The exact single film needs no Layer array (the rare transfer-matrix fallback builds its
        // layer from film_ and thickness_): only the Airy constants, in SoA form, computed for all
        // lanes at once with the operations of squaredIndex and airyFilmConstants (thin_film_stack.cpp),
        // written out: calling those per lane instead made this constructor 1.7x the instructions
        // (5.4 M -> 9.4 M on the thin-film scene in RGB mode, 3 spp) because the loop no longer
        // vectorises.
        const int pad = airyPadded(n_);
        double* a = static_cast<double*>(arena.allocate(sizeof(double) * kAiryArrays * pad, 32));
        double* row[kAiryArrays];
        for (int i = 0; i < kAiryArrays; ++i) row[i] = a + i * pad;
        const SquaredIndex ext = squaredIndex(complexd(extIor_, 0.0));
        alignas(32) double fr[kMaxWavelengths], fi[kMaxWavelengths], sr[kMaxWavelengths], si[kMaxWavelengths],
            lam[kMaxWavelengths];
        for (int k = 0; k < pad; ++k) {
            const int e = std::min(k, n_ - 1);  // padding lanes repeat the last entry
            fr[k] = film_[e].real();
            fi[k] = film_[e].imag();
            sr[k] = substrate_[e].real();
            si[k] = substrate_[e].imag();
            lam[k] = lambda_[e];
        }
        const double d = thickness_;
        for (int k = 0; k < pad; ++k) {  // branch-free, so that the compiler vectorises it (in part)
            const double n1r = fr[k] * fr[k] - fi[k] * fi[k], n1i = fr[k] * fi[k] + fi[k] * fr[k];  // ñ1² (cmul)
            const double n2r = sr[k] * sr[k] - si[k] * si[k], n2i = sr[k] * si[k] + si[k] * sr[k];  // ñ2²
            const double nn1 = n1r * n1r + n1i * n1i, nn2 = n2r * n2r + n2i * n2i;
            row[kN1Re][k] = n1r;
            row[kN1Im][k] = n1i;
            row[kInv1Re][k] = n1r / nn1;  // 1/z = conj(z)/|z|²
            row[kInv1Im][k] = -n1i / nn1;
            row[kK0d][k] = kTwoPi / lam[k] * d;  // k0 d = 2π d/λ
            row[kN2Re][k] = n2r;
            row[kN2Im][k] = n2i;
            row[kInv2Re][k] = n2r / nn2;
            row[kInv2Im][k] = -n2i / nn2;
            row[kExtRe][k] = ext.sq.real();
            row[kExtIm][k] = ext.sq.imag();
            row[kExtInvRe][k] = ext.inv.real();
            row[kExtInvIm][k] = ext.inv.imag();
        }
        airy_ = a;
        airyStride_ = pad;
        return;
    }
    const int stride = 1 + nExtra_;
    layers_ = static_cast<Layer*>(arena.allocate(sizeof(Layer) * n_ * stride, alignof(Layer)));
    for (int k = 0; k < n_; ++k) {
        Layer* r = layers_ + k * stride;
        new (r) Layer{film_[k], thickness_};
        for (int j = 0; j < nExtra_; ++j) new (r + 1 + j) Layer{extraIor(j, k), spec.extra[j].thicknessNm};
    }
}


ThinFilmStackResult ThinFilmCoating::stackRT(int k, double cosTheta) const {
    if (airy_) return exactAt(k, cosTheta, false, airyAngle(cosTheta, extIor_));  // exact single film, hoisted constants
    const int stride = 1 + nExtra_;
    if (nExtra_ == 0)
        return clampedPowers(singleFilmRT(mode_, bounces_, lambda_[k], cosTheta, extIor_, layers_[k * stride], substrate_[k]));
    return thinFilmStackRT(lambda_[k], cosTheta, extIor_, std::span<const Layer>(layers_ + k * stride, stride), substrate_[k]);
}

ThinFilmStackResult ThinFilmCoating::stackRTFromBelow(int k, double cosTheta) const {
    const int stride = 1 + nExtra_;
    const double inc = substrate_[k].real();  // a real dielectric (callers guarantee k = 0)
    if (airy_) return exactAt(k, cosTheta, true, airyAngle(cosTheta, inc));
    if (nExtra_ == 0)
        return clampedPowers(singleFilmRT(mode_, bounces_, lambda_[k], cosTheta, inc, layers_[k * stride], extIor_));
    Layer rev[9];
    for (int j = 0; j < stride; ++j) rev[j] = layers_[k * stride + stride - 1 - j];
    return thinFilmStackRT(lambda_[k], cosTheta, inc, std::span<const Layer>(rev, stride), complexd(extIor_, 0.0));
}

/// Exact single film at entry k (airy_ set: one film, no extra layers) from the hoisted constants
/// and the angle terms of the incident medium (the substrate when `below`). When the fast kernel
/// declines (q1 = 0 exactly, or a non-finite result) the transfer matrix takes over, as in
/// airySingleFilm. exactAll is the same over all entries at once.
inline ThinFilmStackResult ThinFilmCoating::exactAt(int k, double cosTheta, bool below, const AiryAngle& angle) const {
    ThinFilmStackResult r;
    if (airySingleFilmFastAt(angle, airyFilm(k), airySubstrate(k, below), r)) {
        // clampedPowers's result (truncated sums are not energy conserving, thin_film_stack.h): the kernel already returns Rs, Rp ∈ [0, 1] and Ts, Tp ∈ [0, 1],
        // so only T ≤ 1 − R remains (this runs per wavelength per evaluation).
        r.Ts = std::min(r.Ts, 1.0 - r.Rs);
        r.Tp = std::min(r.Tp, 1.0 - r.Rp);
        return r;
    }
    return exactFallback(k, cosTheta, below);
}

ThinFilmStackResult ThinFilmCoating::exactFallback(int k, double cosTheta, bool below) const {
    const double inc = below ? substrate_[k].real() : extIor_;
    const complexd sub = below ? complexd(extIor_, 0.0) : substrate_[k];
    const Layer film{film_[k], thickness_};
    return clampedPowers(thinFilmStackRT(lambda_[k], cosTheta, inc, std::span<const Layer>(&film, 1), sub));
}

uint32_t ThinFilmCoating::airyBatch(double cosTheta, bool below, const AiryBatchOutput& out) const {
    const int pad = airyStride_;
    alignas(32) double s2[kMaxWavelengths], y0s[kMaxWavelengths], y0p[kMaxWavelengths];
    if (!below) {
        const AiryAngle angle = airyAngle(cosTheta, extIor_);
        for (int k = 0; k < pad; ++k) {
            s2[k] = angle.s2;
            y0s[k] = angle.y0s;
            y0p[k] = angle.y0p;
        }
    } else {
        AiryAngle angle;
        double angleIor = -1;  // the incident medium is the substrate: angle terms per distinct index
        for (int k = 0; k < pad; ++k) {
            const double inc = substrate_[std::min(k, n_ - 1)].real();
            if (inc != angleIor) {
                angleIor = inc;
                angle = airyAngle(cosTheta, inc);
            }
            s2[k] = angle.s2;
            y0s[k] = angle.y0s;
            y0p[k] = angle.y0p;
        }
    }
    const int sub = below ? kExtRe : kN2Re;
    const AiryBatchInput in{airyArray(kN1Re), airyArray(kN1Im), airyArray(kInv1Re), airyArray(kInv1Im),
                            airyArray(kK0d), airyArray(AiryArray(sub)), airyArray(AiryArray(sub + 1)),
                            airyArray(AiryArray(sub + 2)), airyArray(AiryArray(sub + 3)), s2, y0s, y0p};
    return airySingleFilmBatch(in, n_, out);
}

void ThinFilmCoating::exactPowersAll(double cosTheta, bool below, double* Rs, double* Rp, double* Ts, double* Tp) const {
    uint32_t declined = airyBatch(cosTheta, below, AiryBatchOutput{Rs, Rp, Ts, Tp});
    while (declined) {  // the rare entries the closed form declines: the transfer matrix (as exactAt)
        const int k = __builtin_ctz(declined);
        declined &= declined - 1;
        const ThinFilmStackResult r = exactFallback(k, cosTheta, below);
        Rs[k] = r.Rs;
        Rp[k] = r.Rp;
        Ts[k] = r.Ts;
        Tp[k] = r.Tp;
    }
}

void ThinFilmCoating::exactAll(double cosTheta, bool below, SampledSpectrum& R, SampledSpectrum* T) const {
    alignas(32) double Rs[kMaxWavelengths], Rp[kMaxWavelengths], Ts[kMaxWavelengths], Tp[kMaxWavelengths];
    exactPowersAll(cosTheta, below, Rs, Rp, Ts, Tp);
    // As exactAt: the kernel's R, T ∈ [0, 1], and T ≤ 1 − R (the fallback's values already satisfy it).
    for (int k = 0; k < n_; ++k) R[k] = float(0.5 * (Rs[k] + Rp[k]));  // ThinFilmStackResult::R()
    if (T)
        for (int k = 0; k < n_; ++k) (*T)[k] = float(0.5 * (std::min(Ts[k], 1.0 - Rs[k]) + std::min(Tp[k], 1.0 - Rp[k])));
}

SampledSpectrum ThinFilmCoating::reflectance(float cosTheta) const {
    SampledSpectrum R(n_);
    if (airy_ && !belcourBarla_ && !cycles42_) {
        exactAll(cosTheta, false, R, nullptr);
        return R;
    }
    for (int k = 0; k < n_; ++k) {
        if (belcourBarla_)
            R[k] = float(belcourBarlaReflectance(k, cosTheta, extIor_, film_[k].real(), thickness_, substrate_[k]));
        else if (cycles42_)
            R[k] = float(cyclesThinFilmRGB(extIor_, film_[k].real(), substrate_[k].real(), cosTheta, thickness_)[k]);
        else
            R[k] = float(stackRT(k, cosTheta).R());
    }
    return R;
}

void ThinFilmCoating::reflectanceTransmittance(float cosTheta, SampledSpectrum& R, SampledSpectrum& T) const {
    R = SampledSpectrum(n_);
    T = SampledSpectrum(n_);
    if (airy_ && !belcourBarla_ && !cycles42_) {
        exactAll(cosTheta, false, R, &T);
        return;
    }
    for (int k = 0; k < n_; ++k) {
        if (cycles42_) {  // dielectric substrate (required): lossless film, T = 1 − R
            R[k] = float(cyclesThinFilmRGB(extIor_, film_[k].real(), substrate_[k].real(), cosTheta, thickness_)[k]);
            T[k] = 1.0f - R[k];
            continue;
        }
        const ThinFilmStackResult r = stackRT(k, cosTheta);
        R[k] = float(r.R());
        T[k] = float(r.T());
        if (belcourBarla_ && substrate_[k].imag() == 0) {
            // Non-absorbing film (required) on a dielectric: T = 1 − R, with the integrated R.
            R[k] = float(belcourBarlaReflectance(k, cosTheta, extIor_, film_[k].real(), thickness_, substrate_[k]));
            T[k] = 1.0f - R[k];
        }
    }
}

void ThinFilmCoating::fromBelowRT(float cosTheta, SampledSpectrum& R, SampledSpectrum& T) const {
    R = SampledSpectrum(n_);
    T = SampledSpectrum(n_);
    if (airy_) {
        exactAll(cosTheta, true, R, &T);
        return;
    }
    for (int k = 0; k < n_; ++k) {
        const ThinFilmStackResult r = stackRTFromBelow(k, cosTheta);
        R[k] = float(r.R());
        T[k] = float(r.T());
    }
}

namespace {

/// The film quadrature: 16 Gauss–Legendre nodes on each side of the critical cosine.
constexpr int kRintNodes = 16;

}  // namespace

double ThinFilmCoating::internalHemisphericalReflectance(int k) const {
    if (!rint_) return internalHemisphericalReflectanceDirect(k);
    if (rgb_) return rint_->rgb[k];
    const float x = (float(lambda_[k]) - kLambdaMin) / ThinFilmCoatingSpec::RintCache::kStep;
    const int last = int(rint_->table.size()) - 1;
    const int i = std::clamp(int(x), 0, last - 1);
    const float t = std::clamp(x - float(i), 0.0f, 1.0f);
    return lerp(t, rint_->table[i], rint_->table[i + 1]);
}

void ThinFilmCoatingSpec::precomputeInternalReflectance(const vec3& rgbLambdas) {
    if (!thickness->isConstant()) return;
    rintCache.reset();  // the coatings below must compute directly
    auto cache = std::make_shared<RintCache>();
    Arena arena;
    const int n = int(std::lround((kLambdaMax - kLambdaMin) / RintCache::kStep)) + 1;
    cache->table.resize(n);
    for (int i = 0; i < n; i += kMaxWavelengths) {  // batches of up to 32 wavelengths
        const int m = std::min(kMaxWavelengths, n - i);
        float lambdas[kMaxWavelengths];
        for (int j = 0; j < m; ++j) lambdas[j] = kLambdaMin + (i + j) * RintCache::kStep;
        const ThinFilmCoating c(*this, TextureQuery{}, lambdas, m, arena);
        for (int j = 0; j < m; ++j) cache->table[i + j] = float(c.internalHemisphericalReflectanceDirect(j));
        arena.reset();
    }
    const SampledWavelengths rgbWl = SampledWavelengths::rgb(rgbLambdas);
    const ThinFilmCoating c(*this, TextureQuery{}, rgbWl, arena);
    for (int k = 0; k < 3; ++k) cache->rgb[k] = float(c.internalHemisphericalReflectanceDirect(k));
    cache->rgbLambdas = rgbLambdas;
    rintCache = std::move(cache);
}

double ThinFilmCoating::internalHemisphericalReflectanceDirect(int k) const {
    const GaussLegendre& g = gaussLegendre(kRintNodes);
    const double nSub = substrate_[k].real();
    // Below μc the exterior wave is evanescent: R = 1 for lossless layers, < 1 with absorption or
    // tunnelling through thin layers, so that part is integrated too (not set to 1).
    const double ratio = extIor_ / nSub;
    const double muC = ratio < 1 ? std::sqrt(1 - ratio * ratio) : 0.0;
    // Above μc, R(μ) has a square-root edge at μc: substitute μ = μc + (1 − μc) t², dμ = 2(1 − μc) t dt,
    // which makes the integrand smooth in t. Below μc, plain Gauss–Legendre in μ.
    double acc = 0;
    for (int i = 0; i < kRintNodes; ++i) {
        if (muC > 0) {
            const double mu = muC * g.x[i];
            acc += muC * g.w[i] * stackRTFromBelow(k, mu).R() * mu;
        }
        const double t = g.x[i], mu = muC + (1 - muC) * t * t;
        acc += g.w[i] * 2 * (1 - muC) * t * stackRTFromBelow(k, mu).R() * mu;
    }
    return std::clamp(2.0 * acc, 0.0, 1.0);
}

}  // namespace iris
