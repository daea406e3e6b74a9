// Shared BSDF test harness; see bsdf_test_util.h for what each check does and why.
#include "tests/support/bsdf_test_util.h"

#include "materials/albedo.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>

#include "core/registry.h"
#include "core/rng.h"
#include "core/sampling.h"
#include "render/loader/scene_upgrade.h"

namespace iris::test {

vec3 dirFromCos(float cosTheta, float phi) {
    const float s = safeSqrt(1.0f - cosTheta * cosTheta);
    return vec3(s * std::cos(phi), s * std::sin(phi), cosTheta);
}

std::shared_ptr<Properties> makeProps(const std::string& type, std::initializer_list<Param> params) {
    auto p = std::make_shared<Properties>("bsdf", type, SourceLocation{"<test>", 0});
    for (const auto& [name, value] : params) p->set(name, value, SourceLocation{"<test>", 0});
    return p;
}

BSDFInstance makeBSDF(const Properties& props, SampledWavelengths wl) {
    BSDFInstance inst;
    inst.material = MaterialRegistry::instance().create(props);
    inst.arena = std::make_unique<Arena>();
    inst.wl = wl;
    ShadingPoint sp;
    inst.bsdf = inst.material->getBSDF(sp, inst.wl, *inst.arena);
    return inst;
}

BSDFInstance makeBSDF(const std::string& type, std::initializer_list<Param> params, SampledWavelengths wl) {
    return makeBSDF(*makeProps(type, params), wl);
}

void asSceneVersion(const PropertiesPtr& p, int formatVersion) {
    p->setFormatVersion(formatVersion);
    ParsedScene scene;
    scene.objects.push_back(p);
    upgradeScene(scene);
}

BSDFInstance makeBSDFVersion(int formatVersion, const std::string& type, std::initializer_list<Param> params,
                             SampledWavelengths wl) {
    const auto p = makeProps(type, params);
    asSceneVersion(p, formatVersion);
    return makeBSDF(*p, wl);
}

double gammaQ(double a, double x) {
    if (x <= 0) return 1.0;
    const double lnPre = -x + a * std::log(x) - std::lgamma(a);
    if (x < a + 1.0) {
        // Series for P(a, x) (Numerical Recipes §6.2.1).
        double ap = a, del = 1.0 / a, sum = del;
        for (int n = 0; n < 10000; ++n) {
            ap += 1.0;
            del *= x / ap;
            sum += del;
            if (std::abs(del) < std::abs(sum) * 1e-15) break;
        }
        return std::max(0.0, 1.0 - sum * std::exp(lnPre));
    }
    // Continued fraction for Q(a, x), modified Lentz (Numerical Recipes §6.2.2, §5.2).
    const double tiny = 1e-300;
    double b = x + 1.0 - a, c = 1.0 / tiny, d = 1.0 / b, h = d;
    for (int i = 1; i < 10000; ++i) {
        const double an = -i * (i - a);
        b += 2.0;
        d = an * d + b;
        if (std::abs(d) < tiny) d = tiny;
        c = b + an / c;
        if (std::abs(c) < tiny) c = tiny;
        d = 1.0 / d;
        const double del = d * c;
        h *= del;
        if (std::abs(del - 1.0) < 1e-15) break;
    }
    return std::exp(lnPre) * h;
}

Chi2Result chi2Test(const BSDF& bsdf, const vec3& wo, const Chi2Options& opt) {
    Chi2Result res;
    const int T = opt.thetaBins, P = opt.phiBins, cells = T * P;
    const double dTheta = M_PI / T, dPhi = 2.0 * M_PI / P;

    // Expected probabilities: composite Simpson over each cell of pdf(θ, φ) sinθ, refined per
    // cell (doubling the points per dimension, from opt.simpsonPoints up to 512) until the
    // change is negligible against the cell's Poisson noise, so narrow lobes are resolved.
    auto simpson = [&](int it, int ip, int n) {
        double acc = 0;
        for (int a = 0; a <= n; ++a) {
            const double wa = (a == 0 || a == n) ? 1.0 : (a % 2 ? 4.0 : 2.0);
            // Nudge the cell's edges inwards so a pdf discontinuous at a cell boundary (the
            // horizon) is integrated with its one-sided limit.
            const double th = (it + std::clamp(double(a) / n, 1e-6, 1.0 - 1e-6)) * dTheta;
            const double st = std::sin(th), ct = std::cos(th);
            for (int b = 0; b <= n; ++b) {
                const double wb = (b == 0 || b == n) ? 1.0 : (b % 2 ? 4.0 : 2.0);
                const double ph = (ip + std::clamp(double(b) / n, 1e-6, 1.0 - 1e-6)) * dPhi;
                const vec3 wi(float(st * std::cos(ph)), float(st * std::sin(ph)), float(ct));
                const float pd = bsdf.pdf(wo, wi, opt.mode);
                if (std::isfinite(pd) && pd > 0) acc += wa * wb * pd * st;
            }
        }
        return acc * (dTheta / (3.0 * n)) * (dPhi / (3.0 * n));
    };
    std::vector<double> expected(cells + 1, 0.0);
    double mass = 0;
    for (int it = 0; it < T; ++it) {
        for (int ip = 0; ip < P; ++ip) {
            int n = std::max(2, opt.simpsonPoints & ~1);
            double p = simpson(it, ip, n);
            while (n < 512) {
                const double p2 = simpson(it, ip, 2 * n);
                const double change = std::abs(p2 - p) * opt.samples;
                p = p2;
                n *= 2;
                if (change < 0.02 * std::sqrt(std::max(1.0, p * opt.samples))) break;
            }
            expected[it * P + ip] = p;
            mass += p;
        }
    }
    res.pdfMass = mass;
    expected[cells] = std::max(0.0, 1.0 - mass);  // failed samples / mass outside the sphere

    std::vector<double> observed(cells + 1, 0.0);
    Sampler rng(opt.seed, 0x5eed5eedull, 0);
    int failed = 0;
    for (int i = 0; i < opt.samples; ++i) {
        const float uc = rng.get1D();
        const vec2 u = rng.get2D();
        const auto s = bsdf.sample(wo, uc, u, opt.mode);
        if (!s || !(s->pdf > 0)) {
            ++failed;
            observed[cells] += 1;
            continue;
        }
        if (s->isSpecular()) {
            res.message = "chi2Test: sample() returned a specular lobe; test delta lobes separately";
            return res;
        }
        const float len = glm::length(s->wi);
        if (!(std::abs(len - 1.0f) < 1e-3f)) {
            res.message = strCat("chi2Test: sampled direction not normalised (|wi| = ", len, ")");
            return res;
        }
        const vec3 wi = s->wi / len;
        const double th = std::acos(std::clamp(double(wi.z), -1.0, 1.0));
        double ph = std::atan2(double(wi.y), double(wi.x));
        if (ph < 0) ph += 2.0 * M_PI;
        const int it = std::clamp(int(th / dTheta), 0, T - 1);
        const int ip = std::clamp(int(ph / dPhi), 0, P - 1);
        observed[it * P + ip] += 1;
    }
    res.failedFraction = double(failed) / opt.samples;
    for (double& e : expected) e *= opt.samples;

    // Pool cells with small expected counts (Mitsuba's chi2 test).
    std::vector<int> order(cells + 1);
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](int a, int b) { return expected[a] < expected[b]; });
    double pooledE = 0, pooledO = 0, chi2 = 0;
    int dof = 0;
    const double minExp = 5.0;
    for (int idx : order) {
        const double e = expected[idx], o = observed[idx];
        if (e == 0.0) {
            if (o > 0) {
                std::ostringstream os;
                os << "chi2Test: " << o << " samples in cell " << idx << " (theta bin " << idx / P << ", phi bin "
                   << idx % P << ") where the integrated pdf is 0";
                res.message = os.str();
                return res;
            }
            continue;
        }
        if (e < minExp || (pooledE > 0 && pooledE < minExp)) {
            pooledE += e;
            pooledO += o;
            continue;
        }
        chi2 += sqr(o - e) / e;
        ++dof;
    }
    if (pooledE > 0) {
        chi2 += sqr(pooledO - pooledE) / pooledE;
        ++dof;
    }
    dof -= 1;
    res.chi2 = chi2;
    res.dof = dof;
    res.threshold = 1.0 - std::pow(1.0 - opt.significance, 1.0 / std::max(1, opt.numTests));
    res.pValue = dof > 0 ? gammaQ(0.5 * dof, 0.5 * chi2) : 1.0;
    res.passed = res.pValue >= res.threshold;
    std::ostringstream os;
    os << "chi2 = " << chi2 << ", dof = " << dof << ", p = " << res.pValue << " (threshold " << res.threshold
       << "), pdf mass = " << mass << ", failed fraction = " << res.failedFraction << ", wo = (" << wo.x << ", "
       << wo.y << ", " << wo.z << ")";
    res.message = os.str();
    return res;
}

namespace {
float relErr(float a, float b) {
    const float m = std::max(std::abs(a), std::abs(b));
    return m > 1e-6f ? std::abs(a - b) / m : 0.0f;
}
}  // namespace

ConsistencyResult checkConsistency(const BSDF& bsdf, const vec3& wo, int samples, uint64_t seed, TransportMode mode) {
    ConsistencyResult r;
    Sampler rng(seed, 0x5eed5eedull, 0);
    for (int i = 0; i < samples; ++i) {
        const float uc = rng.get1D();
        const vec2 u = rng.get2D();
        const auto s = bsdf.sample(wo, uc, u, mode);
        if (!s) continue;
        ++r.samples;
        if (s->f.hasNonFinite() || s->f.hasNegative() || !std::isfinite(s->pdf) || s->pdf < 0) {
            if (r.invalid++ == 0) r.message = strCat("invalid sample value at sample ", i);
            continue;
        }
        if (s->isSpecular()) {
            ++r.specular;
            continue;
        }
        ++r.nonSpecular;
        const SampledSpectrum f = bsdf.eval(wo, s->wi, mode);
        const float pd = bsdf.pdf(wo, s->wi, mode);
        for (int c = 0; c < f.size(); ++c) {
            const float e = relErr(f[c], s->f[c]);
            if (e > r.maxRelErrF) {
                r.maxRelErrF = e;
                r.message = strCat("f: sample ", s->f[c], " vs eval ", f[c], " (channel ", c, ", wi = ", s->wi.x, ", ",
                                   s->wi.y, ", ", s->wi.z, ")");
            }
        }
        const float e = relErr(pd, s->pdf);
        if (e > r.maxRelErrPdf) {
            r.maxRelErrPdf = e;
            r.message = strCat("pdf: sample ", s->pdf, " vs pdf() ", pd, " (wi = ", s->wi.x, ", ", s->wi.y, ", ", s->wi.z,
                               ")");
        }
    }
    return r;
}

namespace {
Estimate finish(double sum, double sum2, int n) { return albedoFromSums(sum, sum2, n); }
}  // namespace

Estimate pdfIntegral(const BSDF& bsdf, const vec3& wo, int samples, uint64_t seed, TransportMode mode) {
    Sampler rng(seed, 0x5eed5eedull, 0);
    double s = 0, s2 = 0;
    for (int i = 0; i < samples; ++i) {
        const vec3 wi = sampleUniformSphere(rng.get2D());
        const double v = double(bsdf.pdf(wo, wi, mode)) / uniformSpherePdf();
        s += v;
        s2 += v * v;
    }
    return finish(s, s2, samples);
}

std::vector<Estimate> albedo(const BSDF& bsdf, const vec3& wo, int samples, uint64_t seed, TransportMode mode) {
    return directionalAlbedo(bsdf, wo, samples, seed, mode);
}

std::pair<Estimate, Estimate> albedoSplit(const BSDF& bsdf, const vec3& wo, int c, int samples, uint64_t seed,
                                          TransportMode mode) {
    Sampler rng(seed, 0x5eed5eedull, 0);
    double r = 0, r2 = 0, t = 0, t2 = 0;
    for (int i = 0; i < samples; ++i) {
        const float uc = rng.get1D();
        const vec2 u = rng.get2D();
        const auto smp = bsdf.sample(wo, uc, u, mode);
        if (!smp) continue;
        const double v = smp->weight()[c];
        if (smp->wi.z * wo.z > 0) {
            r += v;
            r2 += v * v;
        } else {
            t += v;
            t2 += v * v;
        }
    }
    return {finish(r, r2, samples), finish(t, t2, samples)};
}

float reciprocityError(const BSDF& bsdf, int pairs, uint64_t seed, float floor) {
    Sampler rng(seed, 0x5eed5eedull, 0);
    float worst = 0;
    for (int i = 0; i < pairs; ++i) {
        const vec3 a = sampleUniformHemisphere(rng.get2D());
        const vec3 b = sampleUniformHemisphere(rng.get2D());
        if (a.z < 1e-3f || b.z < 1e-3f) continue;
        const SampledSpectrum fab = bsdf.eval(a, b, TransportMode::Radiance);
        const SampledSpectrum fba = bsdf.eval(b, a, TransportMode::Radiance);
        for (int c = 0; c < fab.size(); ++c) {
            const float m = std::max({std::abs(fab[c]), std::abs(fba[c]), floor});
            worst = std::max(worst, std::abs(fab[c] - fba[c]) / m);
        }
    }
    return worst;
}

}  // namespace iris::test
