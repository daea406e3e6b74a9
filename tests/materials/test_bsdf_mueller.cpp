// The BSDFs' Mueller matrices (polarized mode, docs/polarization.md): their response to
// unpolarized light is the spectral BSDF, they are physical (a Stokes vector stays in the cone
// S0 ≥ |S1, S2, S3|), reflection at Brewster's angle has no p part, they are reciprocal where the
// physics is (Q Mᵀ Q in s-axis bases), and the wrappers' frame changes (twosided's mirror, the
// perturbed frame of normal maps) keep the matrix the nested BSDF has in its own frame.
#include <gtest/gtest.h>

#include <random>

#include "core/properties.h"
#include "materials/fresnel_polarized.h"
#include "materials/mueller_frames.h"
#include "spectral/stokes_basis.h"
#include "tests/support/bsdf_test_util.h"

using namespace iris;
using namespace iris::test;

namespace {

const SourceLocation kLoc{"<test>", 0};
SampledWavelengths spectralWl() { return SampledWavelengths::sampleVisible(0.37f, 4); }

std::shared_ptr<Properties> wrap(const std::string& type, std::shared_ptr<Properties> nested, std::initializer_list<Param> params = {}) {
    auto p = makeProps(type, params);
    p->addChild(std::move(nested));
    return p;
}

/// The polarizing BSDFs of the issue, each in a configuration with every lobe present.
std::vector<std::pair<std::string, std::shared_ptr<Properties>>> polarizingBSDFs() {
    auto rc = [] { return makeProps("roughconductor", {{"material", std::string("Au")}, {"alpha", 0.3f}}); };
    auto normalmap = makeProps("normalmap", {});
    normalmap->set("normalmap", RGBValue{vec3(0.6f, 0.45f, 0.9f)}, kLoc);
    normalmap->addChild(rc());
    return {
        {"conductor", makeProps("conductor", {{"material", std::string("Cu")}})},
        {"roughconductor", rc()},
        {"dielectric", makeProps("dielectric", {{"int_ior", 1.6f}})},
        {"roughdielectric", makeProps("roughdielectric", {{"int_ior", 1.6f}, {"alpha", 0.25f}})},
        {"plastic", makeProps("plastic", {{"int_ior", 1.7f}})},
        {"roughplastic", makeProps("roughplastic", {{"alpha", 0.2f}})},
        {"pplastic", makeProps("pplastic", {{"alpha", 0.2f}, {"distribution", std::string("ggx")}})},
        {"twosided", wrap("twosided", rc())},
        {"blendbsdf", [&] { auto b = wrap("blendbsdf", rc(), {{"weight", 0.4f}}); b->addChild(makeProps("diffuse", {})); return b; }()},
        {"mask", wrap("mask", rc(), {{"opacity", 0.7f}})},
        {"normalmap", normalmap},
        {"thinfilm", makeProps("thinfilm", {{"thickness", 350.0f}, {"film_ior", 1.4f}})},
        {"thinfilm rough", makeProps("thinfilm", {{"thickness", 350.0f}, {"alpha", 0.2f}, {"substrate", std::string("dielectric")}})},
        {"thinfilm transmission", makeProps("thinfilm", {{"thickness", 380.0f}, {"film_ior", 1.33f}, {"substrate", std::string("dielectric")},
                                                           {"substrate_eta", 1.5f}, {"transmission", true}})},
        {"thinfilm rough transmission", makeProps("thinfilm", {{"thickness", 380.0f}, {"alpha", 0.3f}, {"substrate", std::string("dielectric")},
                                                                 {"transmission", true}})},
        {"iridescent_diffuse", makeProps("iridescent_diffuse", {{"thickness", 300.0f}})},
        {"iridescent_diffuse rough", makeProps("iridescent_diffuse", {{"thickness", 300.0f}, {"alpha", 0.2f}})},
    };
}

vec3 randomDirection(std::mt19937& rng) {
    std::normal_distribution<float> g;
    return glm::normalize(vec3(g(rng), g(rng), g(rng)));
}

/// A random Stokes vector on or inside the cone S0 = 1 ≥ |S1, S2, S3|.
std::array<float, 4> randomStokes(std::mt19937& rng) {
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    const vec3 d = randomDirection(rng) * (u(rng) < 0.5f ? 1.0f : u(rng));
    return {1.0f, d.x, d.y, d.z};
}

/// M re-expressed in the s-axis bases of normal m (the inverse of fromSAxisBases).
MuellerSpectrum toSAxisBases(const MuellerSpectrum& M, const vec3& m, const vec3& wi, const vec3& wo) {
    const vec3 sIn = glm::normalize(glm::cross(m, -wi)), sOut = glm::normalize(glm::cross(m, wo));
    const auto in = stokesBasisRotation(-wi, stokesBasis(-wi), sIn), out = stokesBasisRotation(wo, stokesBasis(wo), sOut);
    return mueller::rotateBases(M.expanded(), in, out);
}

void expectMuellerNear(const MuellerSpectrum& a, const MuellerSpectrum& b, float tol, const std::string& what) {
    const MuellerSpectrum x = a.expanded(), y = b.expanded();
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j)
            for (int l = 0; l < x.size(); ++l) EXPECT_NEAR(x(i, j)[l], y(i, j)[l], tol) << what << " (" << i << ", " << j << ") lane " << l;
}

}  // namespace

TEST(PolarizedBSDF, UnpolarizedResponseIsTheSpectralBSDF) {
    // M(0, 0) is what the BSDF does to unpolarized light: eval, and sample's f, for every lobe.
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (const auto& [name, props] : polarizingBSDFs()) {
        const auto inst = makeBSDF(*props, spectralWl());
        for (int t = 0; t < 300; ++t) {
            vec3 wo = randomDirection(rng), wi = randomDirection(rng);
            if (name.find("transmission") == std::string::npos && name != "dielectric" && name != "roughdielectric" &&
                name != "twosided" && name != "mask")
                wo.z = std::abs(wo.z);
            const SampledSpectrum f = inst.bsdf->eval(wo, wi, TransportMode::Radiance);
            const MuellerSpectrum M = inst.bsdf->evalMueller(wo, wi, TransportMode::Radiance);
            for (int l = 0; l < 4; ++l) EXPECT_NEAR(M(0, 0)[l], f[l], 2e-4f * (1 + f[l])) << name;
            const float uc = u(rng);
            const vec2 u2(u(rng), u(rng));
            const auto s = inst.bsdf->sample(wo, uc, u2, TransportMode::Radiance);
            const auto ps = inst.bsdf->sampleMueller(wo, uc, u2, TransportMode::Radiance);
            ASSERT_EQ(bool(s), bool(ps)) << name;
            if (!s) continue;
            EXPECT_EQ(s->wi, ps->s.wi) << name;
            EXPECT_EQ(s->pdf, ps->s.pdf) << name;
            for (int l = 0; l < 4; ++l) EXPECT_NEAR(ps->M(0, 0)[l], s->f[l], 2e-4f * (1 + s->f[l])) << name;
        }
    }
}

TEST(PolarizedBSDF, MuellerMatricesArePhysical) {
    // A passive element maps the Stokes cone into itself: S0' ≥ |S1', S2', S3'| for every physical
    // input (the necessary condition of Gil & Bernabeu 1985 on the image of the cone).
    std::mt19937 rng(12);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    auto slab = makeProps("thindielectric", {{"int_ior", 1.7f}});
    auto filter = makeProps("polarizer", {{"theta", 30.0f}});
    auto all = polarizingBSDFs();
    all.push_back({"thindielectric", slab});
    all.push_back({"polarizer", filter});
    all.push_back({"retarder", makeProps("retarder", {{"theta", 20.0f}, {"delta", 70.0f}})});
    all.push_back({"circular", makeProps("circular", {})});
    int checked = 0;
    for (const auto& [name, props] : all) {
        const auto inst = makeBSDF(*props, spectralWl());
        for (int t = 0; t < 400; ++t) {
            const vec3 wo = randomDirection(rng);
            const auto ps = inst.bsdf->sampleMueller(wo, u(rng), vec2(u(rng), u(rng)), TransportMode::Radiance);
            const MuellerSpectrum M = (ps ? ps->M : inst.bsdf->evalMueller(wo, randomDirection(rng), TransportMode::Radiance)).expanded();
            const auto S = randomStokes(rng);
            for (int l = 0; l < 4; ++l) {
                float out[4];
                for (int i = 0; i < 4; ++i) out[i] = M(i, 0)[l] * S[0] + M(i, 1)[l] * S[1] + M(i, 2)[l] * S[2] + M(i, 3)[l] * S[3];
                const float pol = std::sqrt(out[1] * out[1] + out[2] * out[2] + out[3] * out[3]);
                EXPECT_GE(out[0] * (1 + 1e-4f) + 1e-7f, pol) << name << " lane " << l;
                ++checked;
            }
        }
    }
    EXPECT_GT(checked, 20000);
}

TEST(PolarizedBSDF, ReflectionAtBrewstersAngleHasNoPPart) {
    // tan θ_B = η: r_p = 0 (Born & Wolf §1.5.3), so unpolarized light leaves linearly polarized
    // along the s axis, the normal to the plane of incidence.
    const float eta = 1.5f, thetaB = std::atan(eta);
    const InterfaceMuellerTerms t = reflectionTerms(std::cos(thetaB), eta);
    EXPECT_NEAR(t.A - t.B, 0.0f, 1e-7f);  // R_p
    EXPECT_NEAR(t.C, 0.0f, 1e-7f);
    EXPECT_GT(t.A + t.B, 0.1f);  // R_s = 0.148
    const auto inst = makeBSDF("dielectric", {{"int_ior", eta}, {"ext_ior", 1.0f}}, spectralWl());
    const vec3 wo = glm::normalize(vec3(std::sin(thetaB) * std::cos(0.7f), std::sin(thetaB) * std::sin(0.7f), std::cos(thetaB)));
    const auto ps = inst.bsdf->sampleMueller(wo, 0.0f, vec2(0.5f), TransportMode::Radiance);  // uc = 0: the reflection
    ASSERT_TRUE(ps && !ps->s.isTransmission());
    const MuellerSpectrum M = ps->M.expanded();
    // The output of unpolarized input is column 0; in the s-axis basis of the reflected beam it is
    // (S0, S0, 0, 0): fully polarized along s.
    const vec3 sAxis = glm::normalize(glm::cross(vec3(0, 0, 1), wo));
    const auto R = stokesBasisRotation(wo, stokesBasis(wo), sAxis);
    for (int l = 0; l < 4; ++l) {
        const float s0 = M(0, 0)[l], s1 = M(1, 0)[l], s2 = M(2, 0)[l];
        const float s1s = R.c2 * s1 + R.s2 * s2;  // rotator · S
        EXPECT_GT(s0, 0.0f);
        EXPECT_NEAR(s1s / s0, 1.0f, 1e-4f);
        EXPECT_NEAR(M(3, 0)[l], 0.0f, 1e-6f);
    }
}

TEST(PolarizedBSDF, ReciprocalReflectionIsQMTransposeQ) {
    // Reciprocity of Mueller matrices (Sekera 1966; Mitsuba 3 docs "Polarization"): reversing the
    // path transposes the matrix and reverses the sense of the diagonal axis, in the bases that
    // are the same vectors for both paths — here the s axes of the microfacet, Q = diag(1, 1, −1, 1).
    std::mt19937 rng(13);
    for (const auto& [name, props] : polarizingBSDFs()) {
        if (name != "roughconductor" && name != "thinfilm rough" && name != "roughplastic" && name != "pplastic") continue;
        const auto inst = makeBSDF(*props, spectralWl());
        for (int t = 0; t < 200; ++t) {
            vec3 wo = randomDirection(rng), wi = randomDirection(rng);
            wo.z = std::abs(wo.z), wi.z = std::abs(wi.z);
            const vec3 h = glm::normalize(wo + wi);
            const MuellerSpectrum a = toSAxisBases(inst.bsdf->evalMueller(wo, wi, TransportMode::Radiance), h, wi, wo);
            MuellerSpectrum b = toSAxisBases(inst.bsdf->evalMueller(wi, wo, TransportMode::Radiance), h, wo, wi).transposed();
            for (int i = 0; i < 4; ++i)
                for (int j = 0; j < 4; ++j)
                    if ((i == 2) != (j == 2)) b(i, j) = -b(i, j);
            expectMuellerNear(a, b, 2e-4f * (1 + a(0, 0).maxValue()), name);
        }
    }
}

TEST(PolarizedBSDF, TwoSidedBackFaceIsTheMirroredFrontFace) {
    // Seen from behind, twosided's surface is the front one mirrored: in the s-axis bases of the
    // normal on each side the matrices agree, phase terms (D) included — the mirror's change of
    // handedness (materials/mueller_frames.h) is what makes them agree.
    auto rc = makeProps("conductor", {{"material", std::string("Au")}});
    const auto front = makeBSDF(*rc, spectralWl());
    const auto both = makeBSDF(*wrap("twosided", rc), spectralWl());
    std::mt19937 rng(14);
    float maxD = 0;
    for (int t = 0; t < 100; ++t) {
        vec3 wo = randomDirection(rng);
        wo.z = -std::abs(wo.z);
        const auto back = both.bsdf->sampleMueller(wo, 0.5f, vec2(0.5f), TransportMode::Radiance);
        const vec3 woF(wo.x, wo.y, -wo.z);
        const auto fr = front.bsdf->sampleMueller(woF, 0.5f, vec2(0.5f), TransportMode::Radiance);
        ASSERT_TRUE(back && fr);
        const MuellerSpectrum mb = toSAxisBases(back->M, vec3(0, 0, -1), back->s.wi, wo);
        const MuellerSpectrum mf = toSAxisBases(fr->M, vec3(0, 0, 1), fr->s.wi, woF);
        expectMuellerNear(mb, mf, 5e-4f, "twosided back face");
        maxD = std::max(maxD, std::abs(mf(3, 2)[0]));
    }
    EXPECT_GT(maxD, 0.05f);  // gold's phase retardance: the comparison sees D, whose sign the mirror flips
}

TEST(PolarizedBSDF, NormalMappedMirrorIsTheMirrorInThePerturbedFrame) {
    // A smooth conductor under a normal map reflects about the perturbed normal n': in the s-axis
    // bases of n' its matrix is the conductor's own.
    auto cu = makeProps("conductor", {{"material", std::string("Cu")}});
    auto nm = makeProps("normalmap", {{"use_shadowing_function", false}});
    const vec3 rgb(0.62f, 0.41f, 0.88f);
    nm->set("normalmap", RGBValue{rgb}, kLoc);
    nm->addChild(cu);
    const auto mapped = makeBSDF(*nm, spectralWl());
    const auto plain = makeBSDF(*cu, spectralWl());
    const vec3 np = glm::normalize(2.0f * rgb - 1.0f);
    std::mt19937 rng(15);
    for (int t = 0; t < 100; ++t) {
        vec3 wo = randomDirection(rng);
        wo.z = std::abs(wo.z) + 0.3f;
        wo = glm::normalize(wo);
        if (glm::dot(wo, np) < 0.2f) continue;
        const auto s = mapped.bsdf->sampleMueller(wo, 0.5f, vec2(0.5f), TransportMode::Radiance);
        if (!s) continue;
        const float c = glm::dot(wo, np);
        const auto own = plain.bsdf->sampleMueller(dirFromCos(c), 0.5f, vec2(0.5f), TransportMode::Radiance);
        // Same cosine with the normal: compare in s-axis bases (the plain one's about +z). Both
        // delta lobes carry F / |cos θi| (the perturbed one in the unperturbed frame).
        const MuellerSpectrum a = toSAxisBases(s->M, np, s->s.wi, wo) * std::abs(s->s.wi.z);
        const MuellerSpectrum b = toSAxisBases(own->M, vec3(0, 0, 1), own->s.wi, dirFromCos(c)) * c;
        expectMuellerNear(a, b, 2e-4f, "normalmap");
    }
}

TEST(PolarizedBSDF, ZeroThicknessFilmIsTheBareInterface) {
    // thinfilm with d = 0 is the bare substrate: its matrices equal conductor's and dielectric's
    // (Mitsuba 3's fresnel_polarized terms), phase terms included, from both sides of a dielectric
    // and beyond the critical angle.
    const auto film = makeBSDF("thinfilm", {{"thickness", 0.0f}, {"substrate_eta", 0.4f}, {"substrate_k", 2.7f}}, spectralWl());
    const auto metal = makeBSDF("conductor", {{"eta", 0.4f}, {"k", 2.7f}}, spectralWl());
    const auto filmT = makeBSDF("thinfilm", {{"thickness", 0.0f}, {"substrate", std::string("dielectric")}, {"substrate_eta", 1.6f},
                                             {"transmission", true}},
                                spectralWl());
    const auto glass = makeBSDF("dielectric", {{"int_ior", 1.6f}, {"ext_ior", 1.0f}}, spectralWl());
    for (float c : {0.95f, 0.7f, 0.4f, 0.15f}) {
        const vec3 wo = dirFromCos(c, 0.9f);
        expectMuellerNear(film.bsdf->sampleMueller(wo, 0.5f, vec2(0.5f), TransportMode::Radiance)->M,
                          metal.bsdf->sampleMueller(wo, 0.5f, vec2(0.5f), TransportMode::Radiance)->M, 1e-5f / c, "conductor");
        for (const vec3& w : {wo, vec3(wo.x, wo.y, -wo.z)})  // from outside and from inside (TIR below c ≈ 0.78)
            for (float uc : {0.0f, 0.999f}) {  // the reflection and, where there is one, the refraction
                const auto a = filmT.bsdf->sampleMueller(w, uc, vec2(0.5f), TransportMode::Radiance);
                const auto b = glass.bsdf->sampleMueller(w, uc, vec2(0.5f), TransportMode::Radiance);
                ASSERT_EQ(bool(a), bool(b));
                if (!a) continue;
                ASSERT_EQ(a->s.flags & kBSDFTransmission, b->s.flags & kBSDFTransmission);
                expectMuellerNear(a->M, b->M, 2e-5f / c, "dielectric");
            }
    }
}
