#include "render/render_output.h"

#include "core/error.h"
#include "render/integrator.h"
#include "render/scene.h"
#include "render/scene_defaults.h"

namespace iris {

const char* filmColorSpace(bool rgbMode) { return rgbMode ? kColorSpaceLinearRec709 : kColorSpaceXYZ; }

Image filmImage(const Film& film, bool rgbMode, const ColorManager& colors, const std::string& outputSpace) {
    Image out(film.width(), film.height(), 3);
    out.pixels = film.meanImage();
    colors.convert(out.pixels.data(), out.pixelCount(), filmColorSpace(rgbMode), outputSpace);
    return out;
}

ImageMetadata renderMetadata(const Scene& scene, const std::string& scenePath, const Renderer& renderer,
                             const RenderOptions& opt, const RenderStats& st, const ColorManager& colors,
                             const std::string& outputSpace) {
    const vec3& l = opt.rgbWavelengths;
    return {
        {"iris.version", IRIS_VERSION},
        {"iris.scene", scenePath},
        {"iris.mode", opt.rgbMode ? "rgb" : opt.polarized ? "polarized" : "spectral"},
        {"iris.spectral_samples", std::to_string(opt.rgbMode ? 3 : opt.spectralSamples)},
        {"iris.rgb_wavelengths", opt.rgbMode ? strCat(l.x, ",", l.y, ",", l.z) : std::string("")},
        {"iris.wavelength_pdf", opt.rgbMode ? "fixed" : (opt.uniformWavelengths ? "uniform" : "visible")},
        {"iris.wavelength_sampling", opt.rgbMode ? "fixed" : (opt.independentWavelengths ? "independent" : "hero")},
        {"iris.sampler", renderer.samplerName()},
        {"iris.spp", std::to_string(st.sppMin)},
        {"iris.spp_max", std::to_string(st.sppMax)},
        {"iris.spp_target", std::to_string(renderer.targetSpp())},
        {"iris.seed", std::to_string(opt.seed)},
        {"iris.first_sample", std::to_string(opt.firstSample)},
        {"iris.scene_hash", opt.sceneHash},
        {"iris.render_time_s", strCat(st.seconds)},
        {"iris.rays", std::to_string(st.rays)},
        {"iris.invalid_samples", std::to_string(st.invalidSamples)},
        {"iris.interrupted", st.interrupted ? "1" : "0"},
        {"iris.integrator", scene.description().integrator ? scene.description().integrator->type() : std::string(kDefaultIntegrator)},
        {"iris.max_depth", std::to_string(scene.description().integrator ? scene.description().integrator->maxDepth() : -1)},
        {"iris.colorspace", outputSpace},
        {"iris.ocio_config", colors.configPath()},
    };
}

}  // namespace iris
