// Texture-valued scene parameters: a nested <texture> (created through the texture registries of
// core/registry.h) or a plain value wrapped in a constant texture. The material layer's getters
// beside core/properties.h's raw ones and spectral/spectrum_params.h's spectra.
#pragma once

#include <string>

#include "core/properties.h"
#include "materials/textures/texture.h"

namespace iris {

/// Spectrum texture: any spectrum value (spectral/spectrum_params.h), or a nested <texture>.
SpectrumTexturePtr getSpectrumTexture(const Properties& p, const std::string& name, SpectrumKind kind);
SpectrumTexturePtr getSpectrumTexture(const Properties& p, const std::string& name, SpectrumKind kind, float def);
/// Float texture: a float, or a nested <texture>.
FloatTexturePtr getFloatTexture(const Properties& p, const std::string& name);
FloatTexturePtr getFloatTexture(const Properties& p, const std::string& name, float def);

}  // namespace iris
