#include "spectral/ior_presets.h"

#include <cctype>
#include <utility>

#include "core/error.h"

namespace iris {

namespace {
// Mitsuba 3, include/mitsuba/render/ior.h (`ior_data`): "Many values are taken from Hecht, Optics,
// Fourth Edition", measured between 0 and 20 °C at about 589 nm. The same table as the dielectric
// plugin's documentation (which rounds helium and hydrogen to 1.00004 and 1.00013).
const std::pair<const char*, float> kPresets[] = {
    {"vacuum", 1.0f},           {"helium", 1.000036f},      {"hydrogen", 1.000132f},
    {"air", 1.000277f},         {"carbon dioxide", 1.00045f}, {"water", 1.3330f},
    {"acetone", 1.36f},         {"ethanol", 1.361f},        {"carbon tetrachloride", 1.461f},
    {"glycerol", 1.4729f},      {"benzene", 1.501f},        {"silicone oil", 1.52045f},
    {"bromine", 1.661f},        {"water ice", 1.31f},       {"fused quartz", 1.458f},
    {"pyrex", 1.470f},          {"acrylic glass", 1.49f},   {"polypropylene", 1.49f},
    {"bk7", 1.5046f},           {"sodium chloride", 1.544f}, {"amber", 1.55f},
    {"pet", 1.5750f},           {"diamond", 2.419f},
};
}  // namespace

bool lookupIORPreset(const std::string& name, float* eta) {
    std::string lower = name;
    for (char& c : lower) c = char(std::tolower(static_cast<unsigned char>(c)));
    for (const auto& [n, v] : kPresets) {
        if (lower == n) {
            *eta = v;
            return true;
        }
    }
    return false;
}

std::vector<std::string> iorPresetNames() {
    std::vector<std::string> names;
    for (const auto& [n, v] : kPresets) names.emplace_back(n);
    return names;
}

std::string iorPresetList() {
    std::string list;
    for (const auto& [n, v] : kPresets) list += (list.empty() ? "" : ", ") + std::string(n);
    return list;
}

IOR presetIOR(const std::string& name) {
    float eta;
    if (!lookupIORPreset(name, &eta)) fail("unknown IOR preset '", name, "' (known: ", iorPresetList(), ")");
    return IOR::constant(eta);
}

}  // namespace iris
