// Colour management of output images through OpenColorIO 2.1 (config: spectral/ocio/config.ocio).
// The config's reference is scene-linear Rec.709; the film's XYZ is the colour space "CIE-XYZ".
// Config precedence: explicit path (--ocio-config) > $OCIO > the shipped config. OCIO headers stay
// in the .cpp.
#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

namespace iris {

class ColorManager {
public:
    /// configPath: explicit path (--ocio-config); if empty, $OCIO if set, else the shipped
    /// spectral/ocio/config.ocio (core/source_tree.h). Throws iris::Error
    /// naming the file on failure.
    explicit ColorManager(const std::string& configPath = "");
    const std::string& configPath() const;
    bool hasColorSpace(const std::string& name) const;
    std::vector<std::string> colorSpaces() const;
    /// In-place conversion of interleaved RGB float pixels (3 floats per pixel) between colour spaces.
    void convert(float* rgb, size_t pixelCount, const std::string& from, const std::string& to) const;
    /// In-place display/view transform (display "" / view "" = the config's defaults), result in [0,1]-ish display code values.
    void toDisplay(float* rgb, size_t pixelCount, const std::string& from, const std::string& display = "",
                   const std::string& view = "") const;

    /// The shipped config (sourcePath("spectral/ocio/config.ocio")).
    static std::string shippedConfigPath();

private:
    struct Impl;
    std::shared_ptr<const Impl> impl_;
};

constexpr const char* kColorSpaceXYZ = "CIE-XYZ";
constexpr const char* kColorSpaceLinearRec709 = "lin_rec709";

}  // namespace iris
