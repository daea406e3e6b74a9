// Spectrum plugins (spectral/spectrum_plugins.cpp, issue 13 item 4): Mitsuba 3's `<spectrum
// type="...">` objects read from scene XML, each equal to the value form or formula it stands for,
// and their errors located at the scene line.
#include <gtest/gtest.h>

#include "core/error.h"
#include "core/xml/xml_parser.h"
#include "render/loader/scene_loader.h"
#include "spectral/mitsuba_rgb.h"
#include "spectral/spectrum_factory.h"
#include "spectral/spectrum_params.h"

namespace iris {
namespace {

/// The spectrum `name` of the first object of a scene whose body is `inner`, read as `kind`.
SpectrumPtr spectrumOf(const std::string& inner, SpectrumKind kind = SpectrumKind::Reflectance) {
    const ParsedScene scene = parseSceneString("<scene version=\"3.0.0\">\n<bsdf type=\"diffuse\">\n" + inner +
                                               "\n</bsdf>\n</scene>", ".", {});
    return getSpectrum(*scene.objects.at(0), "reflectance", kind);
}

std::string errorOf(const std::string& inner, SpectrumKind kind = SpectrumKind::Reflectance) {
    try {
        spectrumOf(inner, kind);
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

TEST(SpectrumPlugins, RegularAndIrregularEqualTheirPairs) {
    const SpectrumPtr regular = spectrumOf(R"(<spectrum type="regular" name="reflectance">
  <float name="wavelength_min" value="400"/><float name="wavelength_max" value="700"/>
  <string name="values" value="0.1, 0.5, 0.3, 0.9"/></spectrum>)");
    const SpectrumPtr pairs = spectrumOf(R"(<spectrum name="reflectance" value="400:0.1, 500:0.5, 600:0.3, 700:0.9"/>)");
    const SpectrumPtr irregular = spectrumOf(R"(<spectrum type="irregular" name="reflectance">
  <string name="wavelengths" value="400, 500, 600, 700"/><string name="values" value="0.1 0.5 0.3 0.9"/></spectrum>)");
    for (float l = 360; l <= 830; l += 7.5f) {
        EXPECT_EQ(regular->eval(l), pairs->eval(l)) << l;
        EXPECT_EQ(irregular->eval(l), pairs->eval(l)) << l;
    }
    EXPECT_FLOAT_EQ(regular->eval(550), 0.4f);
    EXPECT_EQ(regular->rgbValue(), pairs->rgbValue());  // RGB mode: Mitsuba's projection of the table
}

TEST(SpectrumPlugins, UniformD65BlackbodyAndSrgb) {
    const SpectrumPtr u = spectrumOf(R"(<spectrum type="uniform" name="reflectance"><float name="value" value="0.25"/></spectrum>)");
    EXPECT_EQ(u->eval(400), 0.25f);
    EXPECT_EQ(u->eval(700), 0.25f);
    // An emitter's uniform spectrum is Mitsuba 3's flat emission, not value x D65.
    const SpectrumPtr ue = spectrumOf(R"(<spectrum type="uniform" name="reflectance"><float name="value" value="2"/></spectrum>)",
                                      SpectrumKind::Illuminant);
    EXPECT_EQ(ue->eval(450), mitsuba3UniformEmission(2.0f)->eval(450));
    EXPECT_EQ(ue->rgbValue(), mitsuba3UniformEmission(2.0f)->rgbValue());
    const SpectrumPtr d65 = spectrumOf(R"(<spectrum type="d65" name="reflectance"><float name="scale" value="3"/></spectrum>)",
                                       SpectrumKind::Illuminant);
    EXPECT_EQ(d65->eval(560), makeD65Spectrum(3.0f)->eval(560));
    const SpectrumPtr bb = spectrumOf(R"(<spectrum type="blackbody" name="reflectance"><float name="temperature" value="3000"/></spectrum>)",
                                      SpectrumKind::Illuminant);
    EXPECT_EQ(bb->eval(610), makeBlackbodySpectrum(3000.0f)->eval(610));
    const SpectrumPtr srgb = spectrumOf(R"(<spectrum type="srgb" name="reflectance"><rgb name="color" value="0.2, 0.4, 0.6"/></spectrum>)");
    const SpectrumPtr rgb = spectrumOf(R"(<rgb name="reflectance" value="0.2, 0.4, 0.6"/>)");
    EXPECT_EQ(srgb->eval(520), rgb->eval(520));
    EXPECT_EQ(srgb->rgbValue(), rgb->rgbValue());
}

TEST(SpectrumPlugins, BadObjectsNameTheLineAndWhatIsWrong) {
    EXPECT_NE(errorOf(R"(<spectrum type="rainbow" name="reflectance"/>)").find("<string>:3: unknown spectrum type 'rainbow' (supported: blackbody, d65, irregular, regular, srgb, uniform)"),
              std::string::npos) << errorOf(R"(<spectrum type="rainbow" name="reflectance"/>)");
    EXPECT_NE(errorOf(R"(<spectrum type="regular" name="reflectance"><float name="wavelength_min" value="700"/>
<float name="wavelength_max" value="400"/><string name="values" value="1, 2"/></spectrum>)").find("must exceed wavelength_min"),
              std::string::npos);
    EXPECT_NE(errorOf(R"(<spectrum type="irregular" name="reflectance"><string name="wavelengths" value="400, 500"/>
<string name="values" value="1"/></spectrum>)").find("2 wavelengths but 1 values"), std::string::npos);
    EXPECT_NE(errorOf(R"(<spectrum type="uniform" name="reflectance"><float name="valeu" value="1"/></spectrum>)").find("valeu"),
              std::string::npos);  // an unknown parameter of the plugin
    EXPECT_NE(errorOf(R"(<spectrum type="blackbody" name="reflectance"><float name="temperature" value="-5"/></spectrum>)").find(
                  "temperature must be positive"), std::string::npos);
    EXPECT_NE(errorOf(R"(<spectrum type="uniform"/>)").find("needs a name"), std::string::npos);
}

TEST(SpectrumPlugins, MaterialsAndEmittersTakeThemThroughTheLoader) {
    // The material's texture parameter and an emitter's radiance accept the object form.
    const SceneDescription scene = loadSceneFromString(R"(<scene version="3.0.0">
<shape type="sphere"><bsdf type="diffuse"><spectrum type="irregular" name="reflectance">
  <string name="wavelengths" value="400, 700"/><string name="values" value="0.2, 0.8"/></spectrum></bsdf></shape>
<emitter type="constant"><spectrum type="d65" name="radiance"/></emitter>
</scene>)", ".");
    EXPECT_EQ(scene.shapes.size(), 1u);
    EXPECT_EQ(scene.lights.size(), 1u);
    try {
        loadSceneFromString(R"(<scene version="3.0.0">
<emitter type="constant"><spectrum type="d65" name="radiance"><float name="scale" value="-1"/></spectrum></emitter>
</scene>)", ".");
        ADD_FAILURE() << "a negative d65 scale was accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("<string>:2: d65 scale must be non-negative, got -1"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace iris
