// Tests of the `normalmap` and `bumpmap` wrapper materials: flat maps leave the frame unchanged,
// constant tilted normals tilt it as expected (also from a bitmap file), a linear height ramp tilts
// the normal by atan(scale·slope/|∂p/∂u|) (resp. |∂p/∂v|), the BSDF evaluates the nested one in
// the perturbed frame with Mitsuba 3's flip and shadowing rules, bad input throws.
#include <filesystem>

#include <gtest/gtest.h>

#include "core/error.h"
#include "core/io/image.h"
#include "render/loader/scene_loader.h"
#include "core/registry.h"
#include "materials/material.h"
#include "materials/perturbed_frame.h"
#include "tests/support/bsdf_test_util.h"

namespace iris {
namespace {

/// A linear height field h = slope_u·u + slope_v·v (test-only texture type).
class RampTexture final : public FloatTexture {
public:
    RampTexture(float su, float sv) : su_(su), sv_(sv) {}
    float eval(const TextureQuery& q) const override { return su_ * q.uv.x + sv_ * q.uv.y; }

private:
    float su_, sv_;
};
std::shared_ptr<FloatTexture> createRamp(const Properties& p) {
    return std::make_shared<RampTexture>(p.getFloat("slope_u", 0.0f), p.getFloat("slope_v", 0.0f));
}
IRIS_REGISTER(FloatTextureRegistry, "test_ramp", createRamp);

const SourceLocation kLoc{"<test>", 0};

PropertiesPtr diffuseChild(float r = 0.5f) {
    auto c = std::make_shared<Properties>("bsdf", "diffuse", kLoc);
    c->set("reflectance", r, kLoc);
    return c;
}

std::shared_ptr<Material> create(const PropertiesPtr& p) { return MaterialRegistry::instance().create(*p); }

PropertiesPtr normalMapProps(const vec3& rgb) {
    auto p = std::make_shared<Properties>("bsdf", "normalmap", kLoc);
    p->set("normalmap", RGBValue{rgb}, kLoc);
    p->addChild(diffuseChild());
    return p;
}

PropertiesPtr bumpProps(float slopeU, float slopeV, float scale) {
    auto tex = std::make_shared<Properties>("texture", "test_ramp", kLoc);
    tex->set("slope_u", slopeU, kLoc);
    tex->set("slope_v", slopeV, kLoc);
    auto p = std::make_shared<Properties>("bsdf", "bumpmap", kLoc);
    p->set("height", tex, kLoc);  // Mitsuba: the texture may have any name
    p->set("scale", scale, kLoc);
    p->addChild(diffuseChild());
    return p;
}

/// A shading point with a non-trivial frame (so the tests do not pass by accident in the
/// canonical basis) and the given ∂p/∂u length.
ShadingPoint testPoint(float dpduLength = 1.0f) {
    ShadingPoint sp;
    sp.shading = Frame::fromNormalTangent(glm::normalize(vec3(0.3f, -0.2f, 0.9f)), vec3(1.0f, 0.4f, 0.1f));
    sp.dpdu = dpduLength * sp.shading.s;
    sp.dpdv = dpduLength * sp.shading.t;
    sp.ng = sp.shading.n;
    sp.tex.uv = vec2(0.3f, 0.6f);
    return sp;
}

void expectVecNear(const vec3& a, const vec3& b, float tol, const char* what) {
    EXPECT_NEAR(a.x, b.x, tol) << what;
    EXPECT_NEAR(a.y, b.y, tol) << what;
    EXPECT_NEAR(a.z, b.z, tol) << what;
}

void expectOrthonormal(const Frame& f) {
    EXPECT_NEAR(glm::length(f.s), 1.0f, 1e-5f);
    EXPECT_NEAR(glm::length(f.t), 1.0f, 1e-5f);
    EXPECT_NEAR(glm::length(f.n), 1.0f, 1e-5f);
    EXPECT_NEAR(glm::dot(f.s, f.n), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::dot(f.t, f.n), 0.0f, 1e-5f);
    expectVecNear(glm::cross(f.n, f.s), f.t, 1e-5f, "t = n × s");
}

/// The perturbed frame of a wrapper at sp, in world space (the frame its BSDF evaluates the
/// nested material in for a viewer on the side of the perturbed normal).
Frame perturbedFrame(const Material& m, const ShadingPoint& sp) {
    const auto* pm = dynamic_cast<const PerturbedMaterial*>(&m);
    EXPECT_NE(pm, nullptr);
    return PerturbedMaterial::perturbedPoint(sp, pm->perturbation(sp)).shading;
}

TEST(NormalMap, FlatMapLeavesFrameUnchanged) {
    auto m = create(normalMapProps(vec3(0.5f, 0.5f, 1.0f)));
    const ShadingPoint sp = testPoint();
    const Frame f = perturbedFrame(*m, sp);
    expectVecNear(f.n, sp.shading.n, 1e-6f, "n");
    expectVecNear(f.s, sp.shading.s, 1e-6f, "s");
    expectVecNear(f.t, sp.shading.t, 1e-6f, "t");
    // The integrator keeps the unperturbed frame; the perturbation is inside the BSDF.
    const Frame g = m->shadingFrame(sp);
    expectVecNear(g.n, sp.shading.n, 0.0f, "shadingFrame n");
}

TEST(NormalMap, TiltedConstantNormalTiltsFrame) {
    const ShadingPoint sp = testPoint();
    for (float deg : {10.0f, 30.0f, 60.0f}) {
        const float a = deg * kPi / 180.0f;
        // Tilt towards the tangent s: n' = sin a s + cos a n, s' stays in the (s, n) plane, t' = t.
        auto ms = create(normalMapProps(0.5f * vec3(std::sin(a), 0.0f, std::cos(a)) + 0.5f));
        const Frame fs = perturbedFrame(*ms, sp);
        expectVecNear(fs.n, std::sin(a) * sp.shading.s + std::cos(a) * sp.shading.n, 1e-6f, "n (s tilt)");
        expectVecNear(fs.s, std::cos(a) * sp.shading.s - std::sin(a) * sp.shading.n, 1e-6f, "s (s tilt)");
        expectVecNear(fs.t, sp.shading.t, 1e-6f, "t (s tilt)");
        expectOrthonormal(fs);
        // Tilt towards the bitangent t (green channel).
        auto mt = create(normalMapProps(0.5f * vec3(0.0f, std::sin(a), std::cos(a)) + 0.5f));
        const Frame ft = perturbedFrame(*mt, sp);
        expectVecNear(ft.n, std::sin(a) * sp.shading.t + std::cos(a) * sp.shading.n, 1e-6f, "n (t tilt)");
        expectVecNear(ft.s, sp.shading.s, 1e-6f, "s (t tilt)");
        EXPECT_NEAR(std::acos(std::clamp(glm::dot(ft.n, sp.shading.n), -1.0f, 1.0f)), a, 1e-5f);
        expectOrthonormal(ft);
    }
}

TEST(NormalMap, BitmapNormalMap) {
    // A 4×2 raw EXR bitmap whose texels all hold the normal tilted 30° towards s.
    const float a = 30.0f * kPi / 180.0f;
    const vec3 rgb = 0.5f * vec3(std::sin(a), 0.0f, std::cos(a)) + 0.5f;
    Image img(4, 2, 3);
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 4; ++x)
            for (int c = 0; c < 3; ++c) img.at(x, y, c) = rgb[c];
    const auto path = (std::filesystem::temp_directory_path() / "iris_test_normalmap.exr").string();
    writeEXR(path, img);
    auto tex = std::make_shared<Properties>("texture", "bitmap", kLoc);
    tex->set("filename", path, kLoc);
    tex->set("raw", true, kLoc);
    auto p = std::make_shared<Properties>("bsdf", "normalmap", kLoc);
    p->set("normalmap", tex, kLoc);
    p->addChild(diffuseChild());
    auto m = create(p);
    const ShadingPoint sp = testPoint();
    const Frame f = perturbedFrame(*m, sp);
    expectVecNear(f.n, std::sin(a) * sp.shading.s + std::cos(a) * sp.shading.n, 1e-5f, "n (bitmap)");
    std::filesystem::remove(path);
}

TEST(NormalMap, IdentityMapForwardsNestedBSDF) {
    // (0.5, 0.5, 1) is the unperturbed normal: the shadowing term is 1 (tan θn = 0) and the
    // nested diffuse is returned unchanged, in every direction.
    auto p = normalMapProps(vec3(0.5f, 0.5f, 1.0f));
    auto inst = test::makeBSDF(*p, SampledWavelengths::sampleVisible(0.3f, 4));
    for (float c : {0.9f, 0.5f, 0.05f}) {
        const SampledSpectrum f = inst.bsdf->eval(vec3(0, 0, 1), test::dirFromCos(c, 0.7f), TransportMode::Radiance);
        for (int i = 0; i < f.size(); ++i) EXPECT_FLOAT_EQ(f[i], 0.5f * kInvPi);
    }
}

/// The wrapper of a diffuse (ρ = 0.5) with the map normal tilted by `deg` towards s.
test::BSDFInstance tiltedDiffuse(float deg, bool flip, bool shadow) {
    const float a = deg * kPi / 180.0f;
    auto p = normalMapProps(0.5f * vec3(std::sin(a), 0.0f, std::cos(a)) + 0.5f);
    p->set("flip_invalid_normals", flip, kLoc);
    p->set("use_shadowing_function", shadow, kLoc);
    return test::makeBSDF(*p, SampledWavelengths::rgb(defaultChannelWavelengths()));
}

TEST(NormalMap, EvaluatesNestedInPerturbedFrameWithShadowing) {
    // Mitsuba 3 (PerturbedBSDF::eval) returns f'(wo', wi') |cos θi'| · G(n', wi) with
    // G = 2/(1 + sqrt(1 + α² tan²θi)), α² = tan²θn/8; iris's eval excludes the cosine the
    // integrator takes in the unperturbed frame, so f = ρ/π |cos θi'| / |cos θi| · G.
    const float a = 40.0f * kPi / 180.0f;
    const vec3 n(std::sin(a), 0.0f, std::cos(a));
    const vec3 wo = glm::normalize(vec3(0.2f, 0.1f, 1.0f));
    for (bool shadow : {false, true}) {
        auto inst = tiltedDiffuse(40.0f, true, shadow);
        for (const vec3& wi : {glm::normalize(vec3(0.5f, -0.3f, 0.6f)), glm::normalize(vec3(-0.2f, 0.4f, 0.9f)),
                               glm::normalize(vec3(0.9f, 0.0f, 0.1f))}) {
            const float cosP = glm::dot(wi, n);
            ASSERT_GT(cosP, 0.0f);
            const float alpha2 = 0.125f * std::tan(a) * std::tan(a);
            const float tan2i = (1 - wi.z * wi.z) / (wi.z * wi.z);
            const float g = shadow ? 2.0f / (1.0f + std::sqrt(1.0f + alpha2 * tan2i)) : 1.0f;
            const float expected = 0.5f * kInvPi * cosP / wi.z * g;
            const SampledSpectrum f = inst.bsdf->eval(wo, wi, TransportMode::Radiance);
            EXPECT_NEAR(f[0], expected, 1e-6f * expected) << "shadow " << shadow << " wi.z " << wi.z;
        }
        // wi above the unperturbed normal but below the perturbed one, and the reverse: 0
        // (Mitsuba: both cosines must have one sign).
        const vec3 below = glm::normalize(vec3(-0.95f, 0.0f, 0.3f));  // cos θi' < 0 < cos θi
        ASSERT_LT(glm::dot(below, n), 0.0f);
        EXPECT_EQ(inst.bsdf->eval(wo, below, TransportMode::Radiance)[0], 0.0f);
        EXPECT_EQ(inst.bsdf->pdf(wo, below, TransportMode::Radiance), 0.0f);
        const vec3 under = glm::normalize(vec3(0.95f, 0.0f, -0.2f));  // cos θi < 0 < cos θi'
        ASSERT_GT(glm::dot(under, n), 0.0f);
        EXPECT_EQ(inst.bsdf->eval(wo, under, TransportMode::Radiance)[0], 0.0f);
    }
}

TEST(NormalMap, SilhouetteViewerBelowPerturbedNormalIsFlipped) {
    // At a silhouette the viewer is near the unperturbed horizon, where a tilted map normal often
    // faces away from it: wo · n' < 0 < wo.z. Without flip_invalid_normals the one-sided nested
    // BSDF is black there (iris's behaviour before: the 6–14 % darker silhouettes); Mitsuba 3
    // mirrors n' about n, n' → (−x, −y, z), and shades with that (Schüssler et al. 2017).
    const float a = 40.0f * kPi / 180.0f;
    const vec3 nFlipped(-std::sin(a), 0.0f, std::cos(a));
    const vec3 wo = glm::normalize(vec3(-0.95f, 0.1f, 0.15f));  // grazing, away from the tilt
    ASSERT_LT(glm::dot(wo, vec3(std::sin(a), 0.0f, std::cos(a))), 0.0f);
    const vec3 wi = glm::normalize(vec3(-0.3f, 0.2f, 0.9f));
    auto off = tiltedDiffuse(40.0f, false, false);
    EXPECT_EQ(off.bsdf->eval(wo, wi, TransportMode::Radiance)[0], 0.0f);
    EXPECT_FALSE(off.bsdf->sample(wo, 0.5f, vec2(0.3f, 0.6f), TransportMode::Radiance).has_value());
    auto on = tiltedDiffuse(40.0f, true, false);
    const float expected = 0.5f * kInvPi * glm::dot(wi, nFlipped) / wi.z;
    EXPECT_NEAR(on.bsdf->eval(wo, wi, TransportMode::Radiance)[0], expected, 1e-6f * expected);
    // The flipped lobe is a proper density: sampling, pdf and eval agree, the pdf integrates
    // to the fraction of the perturbed hemisphere above the unperturbed horizon.
    const auto cons = test::checkConsistency(*on.bsdf, wo);
    EXPECT_EQ(cons.invalid, 0) << cons.message;
    EXPECT_LT(cons.maxRelErrF, 1e-4f) << cons.message;
    EXPECT_LT(cons.maxRelErrPdf, 1e-4f) << cons.message;
    const auto chi = test::chi2Test(*on.bsdf, wo);
    EXPECT_TRUE(chi.passed) << chi.message;
}

TEST(NormalMap, OptionsDefaultByVersion) {
    // Version 2.x/3.x: Mitsuba 3 v3.7's flip and shadowing on; 0.x (Mitsuba 0.6): off. Seen at the
    // silhouette configuration above: black without the flip.
    const float a = 40.0f * kPi / 180.0f;
    const vec3 wo = glm::normalize(vec3(-0.95f, 0.1f, 0.15f)), wi = glm::normalize(vec3(-0.3f, 0.2f, 0.9f));
    for (int version : {0, 3}) {
        auto p = normalMapProps(0.5f * vec3(std::sin(a), 0.0f, std::cos(a)) + 0.5f);
        test::asSceneVersion(p, version);  // as the loader reads a file of this version
        auto inst = test::makeBSDF(*p, SampledWavelengths::rgb(defaultChannelWavelengths()));
        const float f = inst.bsdf->eval(wo, wi, TransportMode::Radiance)[0];
        if (version == 0)
            EXPECT_EQ(f, 0.0f);
        else
            EXPECT_GT(f, 0.0f);
    }
}

TEST(NormalMap, WrapperAlbedoAtMostNested) {
    // With the perturbation the diffuse albedo ∫ f |cos θi| dωi = ρ ∫ G |cos θi'|/π over the
    // directions above both horizons stays ≤ ρ (energy is lost, never gained), for any view.
    for (float c : {0.9f, 0.4f, 0.1f}) {
        auto inst = tiltedDiffuse(35.0f, true, true);
        const auto al = test::albedo(*inst.bsdf, test::dirFromCos(c, 2.0f), 200000);
        EXPECT_LE(al[0].mean, 0.5 + 4 * al[0].stderr_) << "cos θo " << c;
        EXPECT_GT(al[0].mean, 0.2) << "cos θo " << c;
    }
}

TEST(NormalMap, NestedInAFlatBumpMapIsUnchanged) {
    // A wrapper around a wrapper: the outer flat bump map (zero gradient: identity frame, G = 1)
    // hands its frames to the inner normal map, whose value must be the same as on its own.
    auto inner = tiltedDiffuse(30.0f, true, true);
    auto tex = std::make_shared<Properties>("texture", "test_ramp", kLoc);
    auto outer = std::make_shared<Properties>("bsdf", "bumpmap", kLoc);
    outer->set("height", tex, kLoc);
    const float a = 30.0f * kPi / 180.0f;
    auto nm = normalMapProps(0.5f * vec3(std::sin(a), 0.0f, std::cos(a)) + 0.5f);
    outer->addChild(nm);
    auto both = test::makeBSDF(*outer, SampledWavelengths::rgb(defaultChannelWavelengths()));
    for (const vec3& wo : {glm::normalize(vec3(0.2f, 0.1f, 1.0f)), glm::normalize(vec3(-0.95f, 0.1f, 0.15f))})
        for (const vec3& wi : {glm::normalize(vec3(0.5f, -0.3f, 0.6f)), glm::normalize(vec3(-0.3f, 0.2f, 0.9f))}) {
            const float e = inner.bsdf->eval(wo, wi, TransportMode::Radiance)[0];
            EXPECT_NEAR(both.bsdf->eval(wo, wi, TransportMode::Radiance)[0], e, 1e-6f * (1 + e));
            EXPECT_NEAR(both.bsdf->pdf(wo, wi, TransportMode::Radiance), inner.bsdf->pdf(wo, wi, TransportMode::Radiance), 1e-6f);
        }
}

TEST(BumpMap, LinearRampTiltsByAtanOfScaledSlope) {
    for (float dpduLen : {1.0f, 2.5f})
        for (float slope : {0.2f, 1.0f, -3.0f})
            for (float scale : {1.0f, 0.5f}) {
                const ShadingPoint sp = testPoint(dpduLen);
                // Central differences in float with δ = 1e-3 at h ~ 2: rounding error ~ ε·h/δ ≈ 2e-4
                // in the gradient, ≲ 5e-5 in the normal, hence the 1e-4 tolerance.
                // Ramp along u: the normal tilts away from the uphill tangent direction s.
                const Frame fu = perturbedFrame(*create(bumpProps(slope, 0.0f, scale)), sp);
                const float tilt = std::atan(scale * slope / dpduLen);
                expectVecNear(fu.n, std::cos(tilt) * sp.shading.n - std::sin(tilt) * sp.shading.s, 1e-4f, "n (u ramp)");
                expectVecNear(fu.t, sp.shading.t, 1e-4f, "t (u ramp)");
                expectOrthonormal(fu);
            }
}

TEST(BumpMap, UsesDpdvOfTheParametrisation) {
    // ∂p/∂u and ∂p/∂v of different lengths (a non-square uv mapping): a ramp along v tilts the
    // normal by atan(scale·slope/|∂p/∂v|), not by the |∂p/∂u| that the old ∂p/∂v ≈ |∂p/∂u| t
    // shortcut used (which gave atan(0.5·1/3) = 9.5° instead of 26.6° here).
    ShadingPoint sp = testPoint(3.0f);
    sp.dpdv = 1.0f * sp.shading.t;
    const float slope = 1.0f, scale = 0.5f;
    const Frame fv = perturbedFrame(*create(bumpProps(0.0f, slope, scale)), sp);
    const float tilt = std::atan(scale * slope / 1.0f);
    expectVecNear(fv.n, std::cos(tilt) * sp.shading.n - std::sin(tilt) * sp.shading.t, 1e-4f, "n (v ramp)");
    expectOrthonormal(fv);
    // Along u, |∂p/∂u| = 3 sets the tilt.
    const Frame fu = perturbedFrame(*create(bumpProps(slope, 0.0f, scale)), sp);
    const float tiltU = std::atan(scale * slope / 3.0f);
    expectVecNear(fu.n, std::cos(tiltU) * sp.shading.n - std::sin(tiltU) * sp.shading.s, 1e-4f, "n (u ramp)");
    // A skewed parametrisation: ∂p/∂v with a component along s; Mitsuba's formula n' ∝ ∂p'/∂u ×
    // ∂p'/∂v, computed here independently.
    sp.dpdv = 0.8f * sp.shading.t + 0.6f * sp.shading.s;
    const Frame fk = perturbedFrame(*create(bumpProps(0.4f, -0.7f, 1.0f)), sp);
    const vec3 du = sp.dpdu + 0.4f * sp.shading.n, dv = sp.dpdv - 0.7f * sp.shading.n;
    expectVecNear(fk.n, glm::normalize(glm::cross(du, dv)), 1e-4f, "n (skewed)");
}

TEST(BumpMap, ConstantHeightLeavesFrameUnchanged) {
    const ShadingPoint sp = testPoint();
    const Frame f = perturbedFrame(*create(bumpProps(0.0f, 0.0f, 5.0f)), sp);
    expectVecNear(f.n, sp.shading.n, 1e-6f, "n");
    expectVecNear(f.s, sp.shading.s, 1e-6f, "s");
}

TEST(NormalMapAndBumpMap, BadInputThrows) {
    {
        auto p = std::make_shared<Properties>("bsdf", "normalmap", kLoc);
        p->set("normalmap", RGBValue{vec3(0.5f, 0.5f, 1.0f)}, kLoc);
        EXPECT_THROW(create(p), Error);  // no nested bsdf
        p->addChild(diffuseChild());
        p->addChild(diffuseChild());
        EXPECT_THROW(create(p), Error);  // two nested bsdfs
    }
    {
        auto p = std::make_shared<Properties>("bsdf", "normalmap", kLoc);
        p->addChild(diffuseChild());
        EXPECT_THROW(create(p), Error);  // no normal map
    }
    {
        auto p = std::make_shared<Properties>("bsdf", "bumpmap", kLoc);
        p->addChild(diffuseChild());
        EXPECT_THROW(create(p), Error);  // no height texture
    }
    {
        auto p = bumpProps(1.0f, 0.0f, 1.0f);
        p->set("gradient_step", 0.0f, kLoc);
        EXPECT_THROW(create(p), Error);
    }
}

TEST(NormalMapAndBumpMap, LoadFromMitsubaXML) {
    // Mitsuba 3 syntax: the normal map under the name "normalmap", the bump texture under an
    // arbitrary name, the nested bsdf unnamed or referenced.
    const std::string xml = R"(<scene version="3.0.0">
  <bsdf type="principled" id="metal"><float name="metallic" value="1"/></bsdf>
  <bsdf type="normalmap" id="nm">
    <rgb name="normalmap" value="0.75 0.5 0.9330127"/>
    <ref id="metal"/>
  </bsdf>
  <bsdf type="bumpmap" id="bump">
    <texture type="checkerboard" name="arbitrary"/>
    <float name="scale" value="0.5"/>
    <bsdf type="cloth"><float name="roughness" value="0.3"/></bsdf>
  </bsdf>
  <shape type="sphere"><ref id="nm"/></shape>
  <shape type="sphere"><ref id="bump"/></shape>
</scene>)";
    const SceneDescription scene = loadSceneFromString(xml, std::filesystem::temp_directory_path().string());
    ASSERT_EQ(scene.shapes.size(), 2u);
    const ShadingPoint sp = testPoint();
    const Frame f = perturbedFrame(*scene.shapes[0].material, sp);
    const float a = 30.0f * kPi / 180.0f;  // (0.75, 0.5, 0.933) = 0.5 + 0.5 (sin 30°, 0, cos 30°)
    expectVecNear(f.n, std::sin(a) * sp.shading.s + std::cos(a) * sp.shading.n, 1e-5f, "n (xml)");
    ASSERT_TRUE(scene.shapes[1].material);
    expectOrthonormal(perturbedFrame(*scene.shapes[1].material, sp));

    const std::string bad = R"(<scene version="3.0.0">
  <bsdf type="bumpmap">
    <float name="scal" value="0.5"/>
    <texture type="checkerboard" name="h"/>
    <bsdf type="diffuse"/>
  </bsdf>
</scene>)";
    try {
        loadSceneFromString(bad, ".");
        ADD_FAILURE() << "expected an iris::Error for the misspelt parameter";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("<string>:3: unknown parameter 'scal'"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace iris
