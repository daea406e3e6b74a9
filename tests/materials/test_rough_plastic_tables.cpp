// Rough dielectric transmittance tables: brute-force integrals (limits, reciprocity), Catmull-Rom
// interpolation error against brute force on random points, disk cache (round trip, corrupt
// files rebuilt, concurrent writers), and laziness (only rough-plastic-type materials acquire the tables).
#include <gtest/gtest.h>

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <thread>
#include <vector>

#include <unistd.h>

#include "core/rng.h"
#include "materials/fresnel.h"
#include "materials/rough_plastic_tables.h"
#include "tests/support/bsdf_test_util.h"

using namespace iris;
using namespace iris::test;

namespace {

std::string tempDir(const std::string& name) {
    const auto d = std::filesystem::temp_directory_path() / ("iris_test_" + name + "_" + std::to_string(::getpid()));
    std::filesystem::create_directories(d);
    return d.string();
}

RoughTableResolution tinyRes() {
    RoughTableResolution r;
    r.nEta = 4;
    r.nAlpha = 5;
    r.nMu = 6;
    r.quadrature = 8;
    return r;
}

}  // namespace

TEST(RoughPlasticTables, BruteForceLimits) {
    for (auto type : {MicrofacetType::Beckmann, MicrofacetType::GGX}) {
        for (double mu : {0.1, 0.5, 1.0}) {
            // α = 0 is the smooth interface; a tiny α is close to it away from grazing.
            const double smooth = 1.0 - fresnelDielectric(float(mu), 1.5f);
            EXPECT_NEAR(roughTransmittanceIntegral(type, 1.5, 0.0, mu), smooth, 1e-7);
            EXPECT_NEAR(roughTransmittanceIntegral(type, 1.5, 0.002, mu), smooth, 1e-3);
            // Index-matched interface: no Fresnel reflection, only masking removes light (the
            // straight-through exit direction is masked more at grazing than a refracted one).
            const double t1 = roughTransmittanceIntegral(type, 1.0, 0.5, mu, 32);
            EXPECT_GT(t1, 0.0);
            EXPECT_LE(t1, 1.0);
            if (mu == 1.0) EXPECT_GT(t1, 0.85);
            // Rougher interfaces and larger η transmit less at normal incidence.
            if (mu == 1.0) {
                EXPECT_GT(roughTransmittanceIntegral(type, 1.5, 0.1, mu), roughTransmittanceIntegral(type, 1.5, 0.8, mu));
                EXPECT_GT(roughTransmittanceIntegral(type, 1.3, 0.3, mu), roughTransmittanceIntegral(type, 2.0, 0.3, mu));
            }
        }
    }
}

TEST(RoughPlasticTables, InternalDiffuseTransmittanceIsReciprocal) {
    // Td from inside computed directly (η → 1/η, with total internal reflection) equals the
    // reciprocity form (1/η²)·(outside hemispherical transmittance) used for the tables.
    for (auto type : {MicrofacetType::Beckmann, MicrofacetType::GGX}) {
        for (double alpha : {0.05, 0.3, 0.8}) {
            const double eta = 1.6;
            const double viaOutside = roughInternalDiffuseIntegral(type, eta, alpha, 32, 48);
            // roughInternalDiffuseIntegral(1/η) = η² · 2∫T_in μ dμ, so the inside hemispherical
            // transmittance 2∫T_in μ dμ is that value divided by η².
            const double tIn = roughInternalDiffuseIntegral(type, 1.0 / eta, alpha, 64, 96) / (eta * eta);
            EXPECT_NEAR(tIn, viaOutside, 2e-3) << "alpha " << alpha;
        }
    }
    // Smooth interface: the classical internal diffuse reflectance for η = 1.5 (≈ 0.596).
    const double fdr = 1.0 - roughInternalDiffuseIntegral(MicrofacetType::Beckmann, 1.5, 0.0, 1, 256);
    EXPECT_NEAR(fdr, 0.596, 0.002);
}

TEST(RoughPlasticTables, InterpolationErrorAgainstBruteForce) {
    // Random points over the whole domain (η ∈ [1, 3], α ∈ [0, 1] with density ∝ 1/sqrt(α),
    // μ ∈ [0, 1]); reference: brute force with 32-point quadrature.
    for (auto type : {MicrofacetType::Beckmann, MicrofacetType::GGX}) {
        const RoughTransmittanceTables& t = roughPlasticTables(type);
        Pcg32 rng(21, 3);
        double maxAll = 0, maxAway = 0, maxTd = 0;
        for (int i = 0; i < 1500; ++i) {
            const float eta = 1.0f + 2.0f * rng.uniform(), a = sqr(rng.uniform()), mu = rng.uniform();
            const double e = std::abs(t.transmittance(eta, a, mu) - roughTransmittanceIntegral(type, eta, a, mu, 32));
            maxAll = std::max(maxAll, e);
            if (mu > 0.1f || a > 0.1f) maxAway = std::max(maxAway, e);
            if (i < 100)
                maxTd = std::max(maxTd, std::abs(t.internalDiffuseTransmittance(eta, a) -
                                                 roughInternalDiffuseIntegral(type, eta, a, 32, 48)));
        }
        std::printf("[tables] %s: max |T error| %.2e (all), %.2e (mu > 0.1 or alpha > 0.1); max |Td error| %.2e\n",
                    type == MicrofacetType::Beckmann ? "beckmann" : "ggx", maxAll, maxAway, maxTd);
        EXPECT_LT(maxAll, 0.03);
        EXPECT_LT(maxAway, 3e-3);
        EXPECT_LT(maxTd, 5e-4);
        // Grid nodes reproduce the stored values.
        const auto& r = t.res;
        for (int ie : {0, r.nEta / 2, r.nEta - 1})
            for (int ia : {0, 3, r.nAlpha - 1})
                for (int im : {0, r.nMu / 3, r.nMu - 1}) {
                    const float v = t.ext[(size_t(ie) * r.nAlpha + ia) * r.nMu + im];
                    EXPECT_NEAR(t.transmittance(RoughTransmittanceTables::etaNode(ie, r.nEta),
                                                RoughTransmittanceTables::alphaNode(ia, r.nAlpha),
                                                RoughTransmittanceTables::muNode(im, r.nMu)),
                                v, 2e-6);
                }
    }
}

TEST(RoughPlasticTables, CacheRoundTripAndCorruptFilesAreRebuilt) {
    const std::string dir = tempDir("cache");
    const std::string path = dir + "/t.bin";
    const RoughTableResolution res = tinyRes();
    const RoughTransmittanceTables fresh = buildRoughTables(MicrofacetType::GGX, res);
    ASSERT_TRUE(writeRoughTables(path, fresh));
    std::string why;
    auto back = readRoughTables(path, MicrofacetType::GGX, res, &why);
    ASSERT_TRUE(back.has_value()) << why;
    EXPECT_EQ(back->ext, fresh.ext);
    EXPECT_EQ(back->diffuse, fresh.diffuse);
    // Wrong distribution or resolution: not accepted.
    EXPECT_FALSE(readRoughTables(path, MicrofacetType::Beckmann, res, &why).has_value());
    RoughTableResolution other = res;
    other.nMu = 7;
    EXPECT_FALSE(readRoughTables(path, MicrofacetType::GGX, other, &why).has_value());

    // Flip one byte in the data: checksum mismatch → warning and rebuild, never a crash.
    {
        std::fstream f(path, std::ios::in | std::ios::out | std::ios::binary);
        f.seekp(60);
        f.put(char(0x5a));
    }
    EXPECT_FALSE(readRoughTables(path, MicrofacetType::GGX, res, &why).has_value());
    RoughTransmittanceTables rebuilt = loadOrBuildRoughTables(path, MicrofacetType::GGX, res);
    EXPECT_EQ(rebuilt.ext, fresh.ext);
    ASSERT_TRUE(readRoughTables(path, MicrofacetType::GGX, res, &why).has_value()) << why;  // rewritten

    // Truncated and garbage files.
    std::filesystem::resize_file(path, 100);
    EXPECT_EQ(loadOrBuildRoughTables(path, MicrofacetType::GGX, res).diffuse, fresh.diffuse);
    { std::ofstream(path, std::ios::binary | std::ios::trunc) << "not a table"; }
    EXPECT_EQ(loadOrBuildRoughTables(path, MicrofacetType::GGX, res).ext, fresh.ext);
    std::filesystem::remove_all(dir);
}

TEST(RoughPlasticTables, CacheSurvivesConcurrentWritersAndReaders) {
    // Two renders starting together both find no cache, both build and both write it (issue 19
    // item 4): writes are atomic renames, so a reader racing them sees no file or a whole one,
    // never a mixed or partial one, and the file left behind is valid.
    const std::string dir = tempDir("concurrent");
    const std::string path = dir + "/t.bin";
    const RoughTableResolution res = tinyRes();
    const RoughTransmittanceTables fresh = buildRoughTables(MicrofacetType::GGX, res);
    std::atomic<bool> writing{true};
    std::atomic<int> wholeReads{0}, badReads{0};
    std::thread reader([&] {
        while (writing) {
            std::string why;
            if (auto t = readRoughTables(path, MicrofacetType::GGX, res, &why)) {
                wholeReads += t->ext == fresh.ext && t->diffuse == fresh.diffuse;
            } else if (why != "missing") {
                ++badReads;
            }
        }
    });
    std::vector<std::thread> writers;
    std::vector<RoughTransmittanceTables> got(4);
    for (int round = 0; round < 20; ++round) {
        std::filesystem::remove(path);
        writers.clear();
        for (size_t i = 0; i < got.size(); ++i)
            writers.emplace_back([&, i] { got[i] = loadOrBuildRoughTables(path, MicrofacetType::GGX, res); });
        for (std::thread& w : writers) w.join();
        for (const RoughTransmittanceTables& t : got) EXPECT_EQ(t.ext, fresh.ext);
    }
    writing = false;
    reader.join();
    EXPECT_EQ(badReads, 0);  // a partial or mixed file would fail the size or checksum test
    std::string why;
    EXPECT_TRUE(readRoughTables(path, MicrofacetType::GGX, res, &why).has_value()) << why;
    std::filesystem::remove_all(dir);
}

TEST(RoughPlasticTables, CachePathKeyedByParameters) {
    RoughTableResolution a, b;
    b.nMu += 1;
    EXPECT_NE(roughTablesCachePath(MicrofacetType::Beckmann, a), roughTablesCachePath(MicrofacetType::GGX, a));
    EXPECT_NE(roughTablesCachePath(MicrofacetType::Beckmann, a), roughTablesCachePath(MicrofacetType::Beckmann, b));
}

TEST(RoughPlasticTables, OnlyRoughPlasticMaterialsAcquireTables) {
    const int b0 = roughPlasticTablesAcquired(MicrofacetType::Beckmann);
    const int g0 = roughPlasticTablesAcquired(MicrofacetType::GGX);
    // Other materials (including smooth plastic and Granier) never touch the tables.
    for (const char* type : {"diffuse", "plastic", "granier"}) {
        auto inst = makeBSDF(type, {});
        ASSERT_NE(inst.bsdf, nullptr);
        inst.bsdf->eval(vec3(0, 0, 1), vec3(0, 0, 1), TransportMode::Radiance);
    }
    EXPECT_EQ(roughPlasticTablesAcquired(MicrofacetType::Beckmann), b0);
    EXPECT_EQ(roughPlasticTablesAcquired(MicrofacetType::GGX), g0);
    // A GGX rough plastic acquires the GGX tables at most once per process, never Beckmann's.
    makeBSDF("roughplastic", {{"distribution", std::string("ggx")}});
    makeBSDF("roughplastic", {{"distribution", std::string("ggx")}, {"alpha", 0.3f}});
    EXPECT_EQ(roughPlasticTablesAcquired(MicrofacetType::GGX), 1);
    EXPECT_EQ(roughPlasticTablesAcquired(MicrofacetType::Beckmann), b0);
}

TEST(RoughPlasticTables, FullResolutionTablesRoundTripThroughTheCache) {
    // Everything the builder writes must be accepted by the reader (values are clamped to [0, 1]).
    const std::string dir = tempDir("fullres");
    const std::string path = dir + "/ggx.bin";
    const RoughTableResolution res;
    const RoughTransmittanceTables built = loadOrBuildRoughTables(path, MicrofacetType::GGX, res);
    std::string why;
    auto back = readRoughTables(path, MicrofacetType::GGX, res, &why);
    ASSERT_TRUE(back.has_value()) << why;
    EXPECT_EQ(back->ext, built.ext);
    std::filesystem::remove_all(dir);
}

TEST(RoughPlasticTables, CacheDirectoryFromEnvironment) {
    const char* old = std::getenv("IRIS_CACHE_DIR");
    const std::string saved = old ? old : "";
    ::setenv("IRIS_CACHE_DIR", "/tmp/iris_cache_env_test", 1);
    EXPECT_EQ(roughTablesCacheDir(), "/tmp/iris_cache_env_test");
    EXPECT_EQ(roughTablesCachePath(MicrofacetType::GGX, RoughTableResolution{}).rfind("/tmp/iris_cache_env_test/", 0), 0u);
    ::unsetenv("IRIS_CACHE_DIR");
    const char* xdg = std::getenv("XDG_CACHE_HOME");
    const char* home = std::getenv("HOME");
    if (xdg && *xdg) EXPECT_EQ(roughTablesCacheDir(), std::string(xdg) + "/iris");
    else if (home && *home) EXPECT_EQ(roughTablesCacheDir(), std::string(home) + "/.cache/iris");
    if (old) ::setenv("IRIS_CACHE_DIR", saved.c_str(), 1);
}

TEST(RoughPlasticTables, ABadTmpdirGivesAWarningNotAnError) {
    // Without IRIS_CACHE_DIR, XDG_CACHE_HOME and HOME the cache goes under $TMPDIR. One that is not
    // a folder (here a plain file) made std::filesystem::temp_directory_path throw, and the render
    // stop with "filesystem error: temp_directory_path"; now the cache path names it and only the
    // write fails, with a warning.
    const std::string file = (std::filesystem::temp_directory_path() / ("iris_tmpdir_file_" + std::to_string(::getpid()))).string();
    std::ofstream(file) << "not a folder";
    const char* names[] = {"IRIS_CACHE_DIR", "XDG_CACHE_HOME", "HOME", "TMPDIR"};
    std::vector<std::pair<std::string, std::optional<std::string>>> saved;
    for (const char* n : names) {
        const char* v = std::getenv(n);
        saved.emplace_back(n, v ? std::optional<std::string>(v) : std::nullopt);
        ::unsetenv(n);
    }
    ::setenv("TMPDIR", file.c_str(), 1);
    std::string dir;
    EXPECT_NO_THROW(dir = roughTablesCacheDir());
    EXPECT_EQ(dir, file + "/iris-cache");
    RoughTableResolution res;
    res.nEta = 4, res.nAlpha = 4, res.nMu = 8;
    RoughTransmittanceTables t;
    EXPECT_NO_THROW(t = loadOrBuildRoughTables(roughTablesCachePath(MicrofacetType::GGX, res), MicrofacetType::GGX, res));
    EXPECT_FALSE(t.ext.empty());  // built, not cached
    for (const auto& [n, v] : saved) v ? ::setenv(n.c_str(), v->c_str(), 1) : ::unsetenv(n.c_str());
    std::filesystem::remove(file);
}

TEST(RoughPlasticTables, CollapsedLinesEqualGeneralInterpolation) {
    // RoughTablesAtAlpha (the α stencil summed once) + collapse (the η stencil summed into one
    // μ-line) read with a 4-node μ stencil (and the lazy etaStencil/transmittance form) must give the tricubic interpolation of eq. 2.44 and
    // the bicubic Td of eq. 2.51 up to float rounding: grid nodes, domain ends, values between
    // nodes and random points, both distributions.
    Pcg32 rng(11, 3);
    for (auto type : {MicrofacetType::Beckmann, MicrofacetType::GGX}) {
        const RoughTransmittanceTables& t = roughPlasticTables(type);
        std::vector<float> alphas = {0.0f, 1e-4f, 1e-3f, 0.08f, 0.124f, 0.5f, 0.999f, 1.0f};
        std::vector<float> etas = {1.0f, 1.0001f, 1.01f, 1.5f, 1.6f, 1.8f, 2.9999f, 3.0f};
        for (int i = 0; i < t.res.nAlpha; i += 3) alphas.push_back(RoughTransmittanceTables::alphaNode(i, t.res.nAlpha));
        for (int i = 0; i < t.res.nEta; i += 3) etas.push_back(RoughTransmittanceTables::etaNode(i, t.res.nEta));
        for (int i = 0; i < 12; ++i) alphas.push_back(rng.uniform());
        for (int i = 0; i < 12; ++i) etas.push_back(1.0f + 2.0f * rng.uniform());
        std::vector<float> mus = {0.0f, 1e-4f, 0.5f / float(t.res.nMu - 1), 0.999f, 1.0f, -0.2f, 1.3f};
        for (int i = 0; i < t.res.nMu; i += 5) mus.push_back(RoughTransmittanceTables::muNode(i, t.res.nMu));
        for (int i = 0; i < 24; ++i) mus.push_back(rng.uniform());
        double maxErrT = 0, maxErrTd = 0;
        int count = 0;
        std::vector<float> line(size_t(t.res.nMu));
        for (float alpha : alphas) {
            const RoughTablesAtAlpha at(t, alpha);
            ASSERT_EQ(at.nMu(), t.res.nMu);
            for (float eta : etas) {
                const float td = at.collapse(eta, line.data());
                maxErrTd = std::max(maxErrTd, double(std::abs(td - t.internalDiffuseTransmittance(eta, alpha))));
                // collapse is deterministic (RGB-mode lines and per-path spectral lines must agree bit for bit).
                std::vector<float> again(line.size());
                ASSERT_EQ(at.collapse(eta, again.data()), td);
                ASSERT_EQ(again, line);
                // The lazy form (η stencil on the α-collapsed tables, spectral mode) is bit-equal.
                const RoughStencil se = at.etaStencil(eta);
                ASSERT_EQ(at.diffuse(se), td);
                for (float mu : mus) {
                    const float fast = roughLineTransmittance(line.data(), roughMuStencil(mu, at.nMu()));
                    ASSERT_EQ(at.transmittance(se, roughMuStencil(mu, at.nMu())), fast) << eta << " " << alpha << " " << mu;
                    const float general = t.transmittance(eta, alpha, mu);
                    maxErrT = std::max(maxErrT, double(std::abs(fast - general)));
                    ++count;
                }
            }
        }
        // Values lie in [0, 1]; the stencil sums have ≤ 64 terms with |weights| ≲ 2.
        EXPECT_LT(maxErrT, 1e-6) << "T, " << count << " points";
        EXPECT_LT(maxErrTd, 1e-6) << "Td";
        std::printf("collapsed vs general: max |ΔT| = %.3g, max |ΔTd| = %.3g over %d points\n", maxErrT, maxErrTd, count);
    }
}

TEST(RoughPlasticTables, CatmullRomStencilWeightsSumToOne) {
    // The interior shortcut and the ghost-folding path of roughCatmullRom both reproduce
    // constants and linear functions (Catmull-Rom with linear extrapolation is exact for them).
    for (int n : {2, 3, 4, 6, 48}) {
        for (int k = 0; k <= 200; ++k) {
            const float x = float(n - 1) * float(k) / 200.0f;
            const RoughStencil s = roughCatmullRom(x, n);
            double sum = 0, lin = 0;
            for (int i = 0; i < s.count; ++i) {
                EXPECT_GE(s.idx[i], 0);
                EXPECT_LT(s.idx[i], n);
                sum += s.w[i];
                lin += s.w[i] * s.idx[i];
            }
            EXPECT_NEAR(sum, 1.0, 1e-6) << n << " " << x;
            EXPECT_NEAR(lin, x, 1e-5 * n) << n << " " << x;
        }
    }
}

TEST(RoughPlasticTables, BatchedChannelStencilsEqualScalarOnes) {
    // RoughTablesAtAlpha::etaStencils and ::transmittances (the SIMD forms the proposed model uses
    // for the channels of a spectral path) must equal the scalar etaStencil / diffuse /
    // transmittance bit for bit: for all channel counts 1..kMaxWavelengths (full groups of four and
    // the scalar remainder), η inside, at and beyond the table ends (ghost stencils), on grid
    // nodes, random η, and μ inside and at the ends of the μ range.
    Pcg32 rng(29, 5);
    int checked = 0, preparedTotal = 0;
    for (auto type : {MicrofacetType::Beckmann, MicrofacetType::GGX}) {
        const RoughTransmittanceTables& t = roughPlasticTables(type);
        for (float alpha : {0.0f, 0.124f, 0.6f, 1.0f}) {
            const RoughTablesAtAlpha at(t, alpha);
            std::vector<float> pool = {1.0f, 1.0001f, 1.002f, 1.01f, 1.5f, 1.6f, 1.8f, 2.9f, 2.999f, 3.0f, 0.9f, 3.5f};
            for (int i = 0; i < t.res.nEta; ++i) pool.push_back(RoughTransmittanceTables::etaNode(i, t.res.nEta));
            std::vector<float> mus = {0.0f, 1e-4f, 0.01f, 0.5f, 0.99f, 0.9999f, 1.0f, -0.1f, 1.2f};
            for (int i = 0; i < 16; ++i) mus.push_back(rng.uniform());
            for (int trial = 0; trial < 60; ++trial) {
                const int n = 1 + trial % kMaxWavelengths;
                float eta[kMaxWavelengths], td[kMaxWavelengths];
                for (int c = 0; c < n; ++c)
                    eta[c] = rng.uniform() < 0.3f ? pool[size_t(rng.uniform() * float(pool.size())) % pool.size()]
                                                  : 1.0f + 2.0f * rng.uniform();
                RoughStencil se[kMaxWavelengths];
                RoughEtaRows rows[kMaxWavelengths];
                at.etaStencils(eta, n, se, td, rows);
                float td2[kMaxWavelengths];
                RoughStencil se2[kMaxWavelengths];
                at.etaStencils(eta, n, se2, td2);  // without the prepared rows: every se[c] written
                for (int c = 0; c < n; ++c) ASSERT_EQ(td2[c], td[c]);
                int prepared = 0;
                for (int c = 0; c < n; ++c) {
                    const RoughStencil ref = at.etaStencil(eta[c]);
                    ASSERT_EQ(se2[c].count, ref.count) << eta[c];
                    for (int k = 0; k < ref.count; ++k) {
                        ASSERT_EQ(se2[c].idx[k], ref.idx[k]) << eta[c];
                        ASSERT_EQ(se2[c].w[k], ref.w[k]) << eta[c];
                    }
                    ASSERT_EQ(td[c], at.diffuse(ref)) << eta[c];
                    if (rows[c].row) {
                        ++prepared;
                        ASSERT_EQ(ref.count, 4) << eta[c];  // only interior stencils are prepared
                    } else {
                        ASSERT_EQ(se[c].count, ref.count) << eta[c];
                        for (int k = 0; k < ref.count; ++k) ASSERT_EQ(se[c].w[k], ref.w[k]) << eta[c];
                    }
                }
                preparedTotal += prepared;
                for (float mu : mus) {
                    const RoughStencil sm = roughMuStencil(mu, at.nMu());
                    float out[kMaxWavelengths], outScalar[kMaxWavelengths];
                    at.transmittances(se, rows, n, sm, out);
                    at.transmittances(se2, nullptr, n, sm, outScalar);
                    for (int c = 0; c < n; ++c) {
                        ASSERT_EQ(out[c], at.transmittance(at.etaStencil(eta[c]), sm)) << eta[c] << " " << mu << " n " << n;
                        ASSERT_EQ(outScalar[c], out[c]);
                        ++checked;
                    }
                }
            }
        }
    }
    EXPECT_GT(checked, 100000);
    EXPECT_GT(preparedTotal, 1000);  // the SIMD path was exercised
}
