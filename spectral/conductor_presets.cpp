#include "spectral/conductor_presets.h"

#include <map>
#include <mutex>

#include "core/error.h"
#include "core/source_tree.h"
#include "spectral/ior_params.h"
#include "spectral/mitsuba_rgb.h"
#include "spectral/spectrum_factory.h"
#include "spectral/spectrum_params.h"

namespace iris {

const std::vector<std::string>& conductorPresetNames() {
    // Mitsuba 3 conductor plugin documentation, table "Conductor presets".
    static const std::vector<std::string> names = {
        "a-C", "Ag",  "Al", "AlAs", "AlSb",     "Au",  "Be",   "Cr",  "CsI", "Cu",      "Cu2O", "CuO", "d-C",
        "Hg",  "HgTe", "Ir", "K",    "Li",       "MgO", "Mo",   "Na_palik", "Nb", "Ni_palik", "Rh", "Se",  "SiC",
        "SnTe", "Ta", "Te", "ThF4", "TiC",      "TiN", "TiO2", "VC",  "V_palik", "VN",  "W",    "none"};
    return names;
}

std::string conductorDataDir() { return sourcePath("spectral/data/ior"); }

ConductorSpectra loadConductorPreset(const std::string& name) {
    if (name == "none") return {};
    const auto& names = conductorPresetNames();
    if (std::find(names.begin(), names.end(), name) == names.end()) {
        std::string list;
        for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
        fail("unknown conductor '", name, "' (known: ", list, ")");
    }
    static std::mutex mutex;
    static std::map<std::string, ConductorSpectra> cache;
    std::lock_guard<std::mutex> lock(mutex);
    auto it = cache.find(name);
    if (it != cache.end()) return it->second;
    ConductorSpectra s;
    const std::string base = conductorDataDir() + "/" + name;
    s.eta = loadSpdFile(base + ".eta.spd", SpectrumKind::Unbounded);
    s.k = loadSpdFile(base + ".k.spd", SpectrumKind::Unbounded);
    cache[name] = s;
    return s;
}

ConductorIOR readConductor(const Properties& p) {
    ConductorIOR s;
    const MitsubaConvention convention = getConvention(p);  // read in every form (core/mitsuba_convention.h)
    const bool hasEta = p.has("eta"), hasK = p.has("k");
    if (hasEta || hasK) {
        if (p.has("material")) failAt(p.locationOf("material"), "give either 'material' or 'eta'/'k', not both");
        if (!(hasEta && hasK)) failAt(p.location(), p.tag(), " '", p.type(), "': 'eta' and 'k' must be given together");
        s.eta = readIOR(p, "eta", IOR(), IorQuantity::ConductorOptics);
        s.k = readIOR(p, "k", IOR(), IorQuantity::ConductorOptics);
    } else {
        // Mitsuba 3: default material "none" (a perfect mirror). A version 0.x scene's conductor
        // got Mitsuba 0.6's "Cu" in the upgrade pass (render/loader/scene_upgrade.h).
        const std::string name = p.getString("material", "none");
        const ConductorSpectra preset = withLocation(p.locationOf("material"), [&] { return loadConductorPreset(name); });
        s.mirror = preset.mirror();
        if (!s.mirror) {
            // RGB mode: the RGB value the RGB variant of the Mitsuba of the object's `convention`
            // computes from the tables (spectral/mitsuba_rgb.h); spectral mode: the tables.
            s.eta = IOR::tabulated(withMitsubaRGBModeValue(preset.eta, MitsubaTableSource::ConductorPreset, convention));
            s.k = IOR::tabulated(withMitsubaRGBModeValue(preset.k, MitsubaTableSource::ConductorPreset, convention));
        }
    }
    // The exterior index η and k are divided by: iris's `ext_ior`, default 1 (Mitsuba 3 has none).
    // Mitsuba 0.6's `extEta` (default "air") became ext_ior in the upgrade pass
    // (render/loader/scene_upgrade.h).
    s.extIOR = readConstantIOR(p, "ext_ior", 1.0f);
    return s;
}

}  // namespace iris
