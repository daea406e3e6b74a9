#include "core/io/spectral_layout.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <numeric>

#include "core/error.h"

namespace iris {

std::string spectralChannelName(double nanometres) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "S0.%.6fnm", nanometres);
    std::string s = buf;
    std::replace(s.begin() + 3, s.end(), '.', ',');  // decimal comma (layout §3.1)
    return s;
}

std::optional<double> parseSpectralChannelName(const std::string& name) {
    if (name.size() < 6 || name.compare(0, 3, "S0.") != 0 || name.compare(name.size() - 2, 2, "nm") != 0) return {};
    std::string number = name.substr(3, name.size() - 5);
    if (number.empty() || number.find_first_not_of("0123456789.,") != std::string::npos) return {};
    std::replace(number.begin(), number.end(), ',', '.');
    char* end = nullptr;
    const double v = std::strtod(number.c_str(), &end);
    if (end != number.c_str() + number.size() || !(v > 0)) return {};
    return v;
}

ImageMetadata spectralLayoutMetadata() { return {{"spectralLayoutVersion", "1.0"}, {"emissiveUnits", "W.m^-2.sr^-1"}}; }

bool hasSpectralChannels(const Image& img) {
    return std::any_of(img.channelNames.begin(), img.channelNames.end(),
                       [](const std::string& n) { return parseSpectralChannelName(n).has_value(); });
}

SpectralImage spectralChannels(const Image& img, const std::string& path) {
    std::vector<std::pair<double, int>> found;  // (wavelength, channel)
    for (int c = 0; c < int(img.channelNames.size()) && c < img.channels; ++c)
        if (const auto l = parseSpectralChannelName(img.channelNames[size_t(c)])) found.emplace_back(*l, c);
    if (found.empty()) fail(path, ": no spectral channels (\"S0.<wavelength>nm\", Fichet et al. 2021)");
    std::sort(found.begin(), found.end());
    for (size_t i = 1; i < found.size(); ++i)
        if (found[i].first == found[i - 1].first) fail(path, ": two spectral channels at ", found[i].first, " nm");
    SpectralImage s;
    s.width = img.width;
    s.height = img.height;
    for (const auto& [l, c] : found) s.wavelengths.push_back(l);
    const size_t bins = found.size();
    s.values.resize(img.pixelCount() * bins);
    for (size_t p = 0; p < img.pixelCount(); ++p)
        for (size_t b = 0; b < bins; ++b) s.values[p * bins + b] = img.pixels[p * size_t(img.channels) + size_t(found[b].second)];
    return s;
}

}  // namespace iris
