#include "materials/textures/texture_params.h"

#include "core/registry.h"
#include "spectral/spectrum_params.h"

namespace iris {

SpectrumTexturePtr getSpectrumTexture(const Properties& props, const std::string& name, SpectrumKind kind) {
    const Properties::Entry& e = props.require(name);
    if (const PropertiesPtr* p = std::get_if<PropertiesPtr>(&e.value); p && (*p)->tag() != "spectrum") {
        const Properties& tp = **p;
        if (tp.tag() != "texture") failAt(e.loc, "parameter '", name, "' must be a texture or spectrum, not a ", tp.tag());
        return SpectrumTextureRegistry::instance().create(tp, kind);
    }
    return constantTexture(getSpectrum(props, name, kind));  // a value or a <spectrum type=...> plugin
}
SpectrumTexturePtr getSpectrumTexture(const Properties& props, const std::string& name, SpectrumKind kind, float def) {
    return props.present(name) ? getSpectrumTexture(props, name, kind) : constantTexture(spectrumFromNumber(def, kind));
}

FloatTexturePtr getFloatTexture(const Properties& props, const std::string& name) {
    const Properties::Entry& e = props.require(name);
    if (const PropertiesPtr* p = std::get_if<PropertiesPtr>(&e.value)) {
        const Properties& tp = **p;
        if (tp.tag() != "texture") failAt(e.loc, "parameter '", name, "' must be a texture or float, not a ", tp.tag());
        return FloatTextureRegistry::instance().create(tp);
    }
    return constantTexture(props.getFloat(name));
}
FloatTexturePtr getFloatTexture(const Properties& props, const std::string& name, float def) {
    return props.present(name) ? getFloatTexture(props, name) : constantTexture(def);
}

}  // namespace iris
