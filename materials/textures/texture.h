// Texture interfaces: material parameters that vary over a surface. Constant textures wrap a
// value; image (bitmap) and procedural textures live in materials/textures/.
#pragma once

#include <memory>

#include "core/math.h"
#include "core/registry.h"
#include "spectral/spectrum.h"

namespace iris {

struct TriangleMesh;

/// Where a texture is looked up. A hit on a triangle mesh also names the mesh, the triangle and
/// the barycentrics (b1, b2) of the hit (weights of the triangle's second and third corners), for
/// the `mesh_attribute` texture; elsewhere `mesh` is nullptr.
struct TextureQuery {
    vec2 uv{0.0f};
    vec3 p{0.0f};
    const TriangleMesh* mesh = nullptr;
    uint32_t triangle = 0;
    vec2 bary{0.0f};
};

class FloatTexture {
public:
    virtual ~FloatTexture() = default;
    virtual float eval(const TextureQuery& q) const = 0;
    /// (∂f/∂u, ∂f/∂v) at q.uv (Mitsuba 3's Texture::eval_1_grad, used by `bumpmap`). The default
    /// takes central differences (f(u+δ) − f(u−δ))/(2δ) with uv step δ = `step`; textures that
    /// know their derivative (bitmap: the bilinear interpolant's, constants: 0) override it.
    virtual vec2 gradient(const TextureQuery& q, float step) const {
        auto at = [&](float du, float dv) {
            TextureQuery s = q;
            s.uv += vec2(du, dv);
            return eval(s);
        };
        const float inv = 0.5f / step;
        return vec2((at(step, 0) - at(-step, 0)) * inv, (at(0, step) - at(0, -step)) * inv);
    }
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
    /// Width and height in texels of an image texture, (1, 1) for others (Mitsuba 3's
    /// Texture::resolution; the projector takes its aspect ratio from it).
    virtual ivec2 resolution() const { return ivec2(1); }
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
    vec2 gradient(const TextureQuery&, float) const override { return vec2(0.0f); }
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
