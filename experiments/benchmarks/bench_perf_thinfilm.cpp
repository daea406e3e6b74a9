// Performance target 4 (docs/performance.md): the exact one-film Airy reflectance at 4 wavelengths
// versus a conductor Fresnel evaluation at 4 wavelengths (the cost of replacing a metal's Fresnel
// term by a thin film over that metal), plus a 10-layer transfer matrix at 4 wavelengths.
// Every benchmark evaluates 4 wavelengths per iteration and varies cosθ so nothing is hoisted.
//   build/bench_perf_thinfilm [--benchmark_format=json]
#include <benchmark/benchmark.h>

#include <vector>

#include "materials/fresnel.h"
#include "spectral/thin_film_airy_batch.h"
#include "spectral/thin_film_airy.h"
#include "spectral/thin_film_stack.h"
#include "spectral/sampled_spectrum.h"

using namespace iris;

namespace {

constexpr int kN = 4;
const double kLambda[kN] = {450.0, 520.0, 590.0, 660.0};
const Layer kFilm{complexd(1.45, 0.0), 420.0};
// Gold-like substrate indices at the four wavelengths (order of magnitude only; cost does not depend on them).
const complexd kMetal[kN] = {{1.4, 1.9}, {0.6, 2.1}, {0.25, 2.9}, {0.16, 3.6}};

float nextCos(float c) { return c < 0.99f ? c + 1e-3f : 0.3f; }

/// Conductor Fresnel (materials/fresnel.h, SampledSpectrum overload) at 4 wavelengths.
void BM_ConductorFresnel4(benchmark::State& st) {
    SampledSpectrum eta(kN), k(kN);
    for (int i = 0; i < kN; ++i) {
        eta[i] = float(kMetal[i].real());
        k[i] = float(kMetal[i].imag());
    }
    float c = 0.3f;
    for (auto _ : st) {
        benchmark::DoNotOptimize(fresnelConductor(c, eta, k));
        c = nextCos(c);
    }
    st.SetItemsProcessed(st.iterations());
}
BENCHMARK(BM_ConductorFresnel4);

/// Exact Airy single film over the conductor (spectral/thin_film_stack.h) at 4 wavelengths.
void BM_AiryFilm4(benchmark::State& st) {
    float c = 0.3f;
    for (auto _ : st) {
        float r[kN];
        for (int i = 0; i < kN; ++i) r[i] = float(airySingleFilm(kLambda[i], c, 1.0, kFilm, kMetal[i]).R());
        benchmark::DoNotOptimize(r);
        c = nextCos(c);
    }
    st.SetItemsProcessed(st.iterations());
}
BENCHMARK(BM_AiryFilm4);

/// The original complex formulation (airySingleFilmReference: std::complex division, cexp, csqrt per
/// polarisation) — what BM_AiryFilm4 measured before the fast path; kept for before/after comparisons.
void BM_AiryFilm4Reference(benchmark::State& st) {
    float c = 0.3f;
    for (auto _ : st) {
        float r[kN];
        for (int i = 0; i < kN; ++i) r[i] = float(airySingleFilmReference(kLambda[i], c, 1.0, kFilm, kMetal[i]).R());
        benchmark::DoNotOptimize(r);
        c = nextCos(c);
    }
    st.SetItemsProcessed(st.iterations());
}
BENCHMARK(BM_AiryFilm4Reference);

/// The fast path as ThinFilmCoating uses it: film ñ1², 1/ñ1², k0 d and the substrate's ñ², 1/ñ² hoisted
/// once per path (here: outside the loop), only the angle-dependent work per evaluation.
void BM_AiryFilm4Hoisted(benchmark::State& st) {
    AiryFilmConstants film[kN];
    SquaredIndex sub[kN];
    for (int i = 0; i < kN; ++i) {
        film[i] = airyFilmConstants(kLambda[i], kFilm);
        sub[i] = squaredIndex(kMetal[i]);
    }
    float c = 0.3f;
    for (auto _ : st) {
        float r[kN];
        for (int i = 0; i < kN; ++i) {
            ThinFilmStackResult res;
            if (!airySingleFilmFast(c, 1.0, film[i], sub[i], res))
                res = airySingleFilmReference(kLambda[i], c, 1.0, kFilm, kMetal[i]);
            r[i] = float(res.R());
        }
        benchmark::DoNotOptimize(r);
        c = nextCos(c);
    }
    st.SetItemsProcessed(st.iterations());
}
BENCHMARK(BM_AiryFilm4Hoisted);

/// The batched kernel as ThinFilmCoating calls it (spectral/thin_film_airy_batch.h): the four wavelengths in
/// one SIMD group, constants hoisted into SoA arrays, the angle terms per evaluation.
void BM_AiryFilm4Batch(benchmark::State& st) {
    alignas(32) double v[9][kN];
    for (int i = 0; i < kN; ++i) {
        const AiryFilmConstants f = airyFilmConstants(kLambda[i], kFilm);
        const SquaredIndex s = squaredIndex(kMetal[i]);
        const double x[9] = {f.n1sq.real(), f.n1sq.imag(), f.invN1sq.real(), f.invN1sq.imag(), f.k0d,
                             s.sq.real(), s.sq.imag(), s.inv.real(), s.inv.imag()};
        for (int a = 0; a < 9; ++a) v[a][i] = x[a];
    }
    float c = 0.3f;
    for (auto _ : st) {
        alignas(32) double s2[kN], y0s[kN], y0p[kN], Rs[kN], Rp[kN], Ts[kN], Tp[kN];
        const AiryAngle angle = airyAngle(c, 1.0);
        for (int i = 0; i < kN; ++i) {
            s2[i] = angle.s2;
            y0s[i] = angle.y0s;
            y0p[i] = angle.y0p;
        }
        const AiryBatchInput in{v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], v[8], s2, y0s, y0p};
        const uint32_t declined = airySingleFilmBatch(in, kN, AiryBatchOutput{Rs, Rp, Ts, Tp});
        float r[kN];
        for (int i = 0; i < kN; ++i)
            r[i] = declined >> i & 1 ? float(airySingleFilm(kLambda[i], c, 1.0, kFilm, kMetal[i]).R())
                                     : float(0.5 * (Rs[i] + Rp[i]));
        benchmark::DoNotOptimize(r);
        c = nextCos(c);
    }
    st.SetItemsProcessed(st.iterations());
}
BENCHMARK(BM_AiryFilm4Batch);

/// Transfer matrix through `range(0)` layers over the conductor at 4 wavelengths.
void BM_TransferMatrix4(benchmark::State& st) {
    std::vector<Layer> layers;
    for (int j = 0; j < st.range(0); ++j)  // alternating high/low index quarter-wave-like stack
        layers.push_back(j % 2 ? Layer{complexd(1.38, 0.0), 100.0} : Layer{complexd(2.35, 0.0), 60.0});
    float c = 0.3f;
    for (auto _ : st) {
        float r[kN];
        for (int i = 0; i < kN; ++i) r[i] = float(thinFilmStackRT(kLambda[i], c, 1.0, layers, kMetal[i]).R());
        benchmark::DoNotOptimize(r);
        c = nextCos(c);
    }
    st.SetItemsProcessed(st.iterations());
}
BENCHMARK(BM_TransferMatrix4)->Arg(1)->Arg(10);

}  // namespace

BENCHMARK_MAIN();
