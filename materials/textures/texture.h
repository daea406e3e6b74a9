// Texture interfaces: material parameters that vary over a surface. Constant textures wrap a
// value; image (bitmap) and procedural textures live in materials/textures/.
#pragma once

#include <memory>

#include "core/math.h"
#include "core/registry.h"
#include "spectral/spectrum.h"

namespace iris {

/// Where a texture is looked up.
struct TextureQuery {
    vec2 uv{0.0f};
    vec3 p{0.0f};
};

class FloatTexture {
public:
    virtual ~FloatTexture() = default;
    virtual float eval(const TextureQuery& q) const = 0;
    /// True when eval does not depend on the query (lets materials precompute).
    virtual bool isConstant() const { return false; }
};

class SpectrumTexture {
public:
    virtual ~SpectrumTexture() = default;
    virtual SampledSpectrum eval(const TextureQuery& q, const SampledWavelengths& wl) const = 0;
    virtual bool isConstant() const { return false; }
    /// For constant textures, the spectrum (else nullptr).
    virtual const Spectrum* constantSpectrum() const { return nullptr; }
};

using FloatTexturePtr = std::shared_ptr<const FloatTexture>;
using SpectrumTexturePtr = std::shared_ptr<const SpectrumTexture>;
/// Texture types by scene-file name; a spectrum texture is told which kind of spectrum it holds.
using SpectrumTextureRegistry = Registry<SpectrumTexture, SpectrumKind>;
using FloatTextureRegistry = Registry<FloatTexture>;

class ConstantFloatTexture final : public FloatTexture {
public:
    explicit ConstantFloatTexture(float v) : v_(v) {}
    float eval(const TextureQuery&) const override { return v_; }
    bool isConstant() const override { return true; }
    float value() const { return v_; }

private:
    float v_;
};

class ConstantSpectrumTexture final : public SpectrumTexture {
public:
    explicit ConstantSpectrumTexture(SpectrumPtr s) : s_(std::move(s)) {}
    SampledSpectrum eval(const TextureQuery&, const SampledWavelengths& wl) const override { return s_->sample(wl); }
    bool isConstant() const override { return true; }
    const Spectrum* constantSpectrum() const override { return s_.get(); }

private:
    SpectrumPtr s_;
};

inline FloatTexturePtr constantTexture(float v) { return std::make_shared<ConstantFloatTexture>(v); }
inline SpectrumTexturePtr constantTexture(SpectrumPtr s) { return std::make_shared<ConstantSpectrumTexture>(std::move(s)); }

}  // namespace iris
