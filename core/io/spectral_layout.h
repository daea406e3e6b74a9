// The OpenEXR layout for spectral images of Fichet, Pacanowski & Wilkie ("An OpenEXR Layout for
// Spectral Images", JCGT 10(3), 2021, §3): an emissive, unpolarised spectral image stores one FLOAT
// channel per wavelength named "S0.<wavelength>nm", the wavelength written with a comma as the
// decimal separator ("S0.552,500000nm"), and the header attributes spectralLayoutVersion = "1.0"
// and emissiveUnits = "W.m^-2.sr^-1". Other channels (R, G, B, ...) may sit beside them.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/io/image.h"

namespace iris {

/// "S0.<nm>nm" with six decimals and a decimal comma (§3.1 of the layout).
std::string spectralChannelName(double nanometres);
/// The wavelength (nm) of an emissive Stokes-0 channel name ("S0.550nm", "S0.552,5nm", also with a
/// decimal point as some writers use), or nothing for any other name.
std::optional<double> parseSpectralChannelName(const std::string& name);

/// The header attributes the layout requires for an emissive image.
ImageMetadata spectralLayoutMetadata();

/// The spectral channels of an image, sorted by wavelength.
struct SpectralImage {
    int width = 0, height = 0;
    std::vector<double> wavelengths;  // nm, increasing
    std::vector<float> values;        // pixel-major: values[(y * width + x) * bins + b]
    int bins() const { return int(wavelengths.size()); }
};

/// True when the image has at least one "S0.*nm" channel.
bool hasSpectralChannels(const Image& img);
/// The "S0.*nm" channels of `img`; throws iris::Error naming `path` if it has none or two
/// channels name the same wavelength.
SpectralImage spectralChannels(const Image& img, const std::string& path);

}  // namespace iris
