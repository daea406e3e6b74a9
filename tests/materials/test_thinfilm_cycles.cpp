// The thinfilm material's rgb_mode "cycles_4_2" (Blender Cycles 4.2's thin film,
// spectral/thin_film_cycles.h): used in RGB mode only, dielectric substrates only.
#include <gtest/gtest.h>

#include "core/registry.h"
#include "spectral/thin_film_cycles.h"
#include "spectral/thin_film_stack.h"
#include "tests/support/bsdf_test_util.h"

using namespace iris;
using namespace iris::test;

namespace {
const std::string S(const char* s) { return s; }
}  // namespace

TEST(ThinFilmCyclesMaterial, RgbModeReadsCyclesAndSpectralModeIsExact) {
    const auto film = [](const SampledWavelengths& wl) {
        return makeBSDF("thinfilm", {{"substrate", S("dielectric")}, {"substrate_eta", 1.5f}, {"thickness", 450.0f},
                                     {"film_ior", 1.33f}, {"rgb_mode", S("cycles_4_2")}}, wl);
    };
    const vec3 wo = dirFromCos(0.8f);
    const SampledWavelengths rgb = SampledWavelengths::rgb(defaultChannelWavelengths());
    auto cycles = film(rgb);
    const SampledSpectrum fc = cycles.bsdf->sample(wo, 0.5f, vec2(0.5f), TransportMode::Radiance)->weight();
    const dvec3 expected = cyclesThinFilmRGB(1.0, 1.33, 1.5, 0.8, 450.0);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(fc[c], expected[c], 1e-6) << c;
    // Spectral mode ignores rgb_mode: the exact film at each wavelength.
    const SampledWavelengths wl = SampledWavelengths::sampleVisible(0.37f, 4);
    auto spectral = film(wl);
    const SampledSpectrum fs = spectral.bsdf->sample(wo, 0.5f, vec2(0.5f), TransportMode::Radiance)->weight();
    for (int k = 0; k < wl.size(); ++k)
        EXPECT_NEAR(fs[k], airySingleFilm(wl.lambda(k), 0.8, 1.0, Layer{1.33, 450.0}, complexd(1.5, 0.0)).R(), 2e-6);
}

TEST(ThinFilmCyclesMaterial, MetalsAndUnknownModesAreRejected) {
    // Cycles 4.2 has no film on metals: a conductor substrate is an error, as are an absorbing
    // film, extra layers, transmission and a misspelt mode.
    EXPECT_THROW(makeBSDF("thinfilm", {{"rgb_mode", S("cycles_4_2")}}), Error);  // default substrate: conductor
    EXPECT_THROW(makeBSDF("thinfilm", {{"substrate", S("dielectric")}, {"rgb_mode", S("cycles_4_2")}, {"film_k", 0.1f}}), Error);
    EXPECT_THROW(makeBSDF("thinfilm", {{"substrate", S("dielectric")}, {"rgb_mode", S("cycles_4_2")}, {"layer1_ior", 2.0f},
                                       {"layer1_thickness", 5.0f}}),
                 Error);
    EXPECT_THROW(makeBSDF("thinfilm", {{"substrate", S("dielectric")}, {"rgb_mode", S("cycles_4_2")}, {"transmission", true}}), Error);
    EXPECT_THROW(makeBSDF("thinfilm", {{"substrate", S("dielectric")}, {"rgb_mode", S("cycles")}}), Error);
    EXPECT_NO_THROW(makeBSDF("thinfilm", {{"substrate", S("dielectric")}, {"rgb_mode", S("cycles_4_2")}}));
}
