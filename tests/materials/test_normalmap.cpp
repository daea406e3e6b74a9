// Tests of the `normalmap` and `bumpmap` wrapper materials: flat maps leave the frame unchanged,
// constant tilted normals tilt it as expected (also from a bitmap file), a linear height ramp tilts
// the normal by atan(scale·slope/|∂p/∂u|), the nested BSDF is forwarded, bad input throws.
#include <filesystem>

#include <gtest/gtest.h>

#include "core/error.h"
#include "core/io/image.h"
#include "render/loader/scene_loader.h"
#include "core/registry.h"
#include "materials/material.h"
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

TEST(NormalMap, FlatMapLeavesFrameUnchanged) {
    auto m = create(normalMapProps(vec3(0.5f, 0.5f, 1.0f)));
    const ShadingPoint sp = testPoint();
    const Frame f = m->shadingFrame(sp);
    expectVecNear(f.n, sp.shading.n, 1e-6f, "n");
    expectVecNear(f.s, sp.shading.s, 1e-6f, "s");
    expectVecNear(f.t, sp.shading.t, 1e-6f, "t");
}

TEST(NormalMap, TiltedConstantNormalTiltsFrame) {
    const ShadingPoint sp = testPoint();
    for (float deg : {10.0f, 30.0f, 60.0f}) {
        const float a = deg * kPi / 180.0f;
        // Tilt towards the tangent s: n' = sin a s + cos a n, s' stays in the (s, n) plane, t' = t.
        auto ms = create(normalMapProps(0.5f * vec3(std::sin(a), 0.0f, std::cos(a)) + 0.5f));
        const Frame fs = ms->shadingFrame(sp);
        expectVecNear(fs.n, std::sin(a) * sp.shading.s + std::cos(a) * sp.shading.n, 1e-6f, "n (s tilt)");
        expectVecNear(fs.s, std::cos(a) * sp.shading.s - std::sin(a) * sp.shading.n, 1e-6f, "s (s tilt)");
        expectVecNear(fs.t, sp.shading.t, 1e-6f, "t (s tilt)");
        expectOrthonormal(fs);
        // Tilt towards the bitangent t (green channel).
        auto mt = create(normalMapProps(0.5f * vec3(0.0f, std::sin(a), std::cos(a)) + 0.5f));
        const Frame ft = mt->shadingFrame(sp);
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
    const Frame f = m->shadingFrame(sp);
    expectVecNear(f.n, std::sin(a) * sp.shading.s + std::cos(a) * sp.shading.n, 1e-5f, "n (bitmap)");
    std::filesystem::remove(path);
}

TEST(NormalMap, ForwardsNestedBSDF) {
    auto p = normalMapProps(vec3(0.7f, 0.4f, 0.9f));
    auto inst = test::makeBSDF(*p, SampledWavelengths::sampleVisible(0.3f, 4));
    const SampledSpectrum f = inst.bsdf->eval(vec3(0, 0, 1), test::dirFromCos(0.5f), TransportMode::Radiance);
    for (int i = 0; i < f.size(); ++i) EXPECT_FLOAT_EQ(f[i], 0.5f * kInvPi);
}

TEST(BumpMap, LinearRampTiltsByAtanOfScaledSlope) {
    for (float dpduLen : {1.0f, 2.5f})
        for (float slope : {0.2f, 1.0f, -3.0f})
            for (float scale : {1.0f, 0.5f}) {
                const ShadingPoint sp = testPoint(dpduLen);
                // Central differences in float with δ = 1e-3 at h ~ 2: rounding error ~ ε·h/δ ≈ 2e-4
                // in the gradient, ≲ 5e-5 in the normal, hence the 1e-4 tolerance.
                // Ramp along u: the normal tilts away from the uphill tangent direction s.
                const Frame fu = create(bumpProps(slope, 0.0f, scale))->shadingFrame(sp);
                const float tilt = std::atan(scale * slope / dpduLen);
                expectVecNear(fu.n, std::cos(tilt) * sp.shading.n - std::sin(tilt) * sp.shading.s, 1e-4f, "n (u ramp)");
                expectVecNear(fu.t, sp.shading.t, 1e-4f, "t (u ramp)");
                expectOrthonormal(fu);
                // Ramp along v: tilts away from t.
                const Frame fv = create(bumpProps(0.0f, slope, scale))->shadingFrame(sp);
                expectVecNear(fv.n, std::cos(tilt) * sp.shading.n - std::sin(tilt) * sp.shading.t, 1e-4f, "n (v ramp)");
                expectOrthonormal(fv);
                EXPECT_NEAR(std::acos(std::clamp(glm::dot(fv.n, sp.shading.n), -1.0f, 1.0f)), std::abs(tilt), 1e-4f);
            }
}

TEST(BumpMap, ConstantHeightLeavesFrameUnchanged) {
    const ShadingPoint sp = testPoint();
    const Frame f = create(bumpProps(0.0f, 0.0f, 5.0f))->shadingFrame(sp);
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
    const Frame f = scene.shapes[0].material->shadingFrame(sp);
    const float a = 30.0f * kPi / 180.0f;  // (0.75, 0.5, 0.933) = 0.5 + 0.5 (sin 30°, 0, cos 30°)
    expectVecNear(f.n, std::sin(a) * sp.shading.s + std::cos(a) * sp.shading.n, 1e-5f, "n (xml)");
    ASSERT_TRUE(scene.shapes[1].material);
    expectOrthonormal(scene.shapes[1].material->shadingFrame(sp));

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
