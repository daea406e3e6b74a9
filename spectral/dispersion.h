// Index of refraction as a function of wavelength, η(λ), for dielectrics:
//   constant; Cauchy η = A + B/λ² (λ in µm; Cauchy 1836, e.g. Born & Wolf §2.3.4);
//   Sellmeier η² = 1 + Σ_{i=1..3} B_i λ² / (λ² − C_i) (λ in µm, C_i in µm²; Sellmeier 1871,
//   coefficients as in the Schott catalogue); a tabulated spectrum; or three per-channel values
//   (η_R, η_G, η_B at the RGB channel wavelengths, default 645/525/445 nm), piecewise linear in λ
//   with constant extrapolation, returned exactly in RGB mode.
// Plus Mitsuba's named IOR presets ("bk7", "water", ...), so `int_ior`/`ext_ior` may be names.
#pragma once

#include <string>
#include <vector>

#include "core/properties.h"
#include "spectral/spectrum.h"

namespace iris {

class IOR {
public:
    enum class Kind { Constant, Cauchy, Sellmeier, Tabulated, PerChannel };

    static IOR constant(float eta);
    static IOR cauchy(float a, float bUm2);
    static IOR sellmeier(const vec3& b, const vec3& cUm2);
    static IOR tabulated(SpectrumPtr spectrum);
    /// (η_R, η_G, η_B) at channel wavelengths (λ_R, λ_G, λ_B) in nm.
    static IOR perChannel(const vec3& eta, const vec3& lambdas = vec3(645, 525, 445));

    Kind kind() const { return kind_; }
    /// η at one wavelength (nm).
    float eval(float lambda) const;
    /// η at the path's wavelengths. RGB mode: PerChannel returns its three values exactly;
    /// other kinds are evaluated at the channel wavelengths (a constant stays exact).
    SampledSpectrum sample(const SampledWavelengths& wl) const;
    /// True when η varies with wavelength (refracted directions depend on λ).
    bool isDispersive() const;

private:
    Kind kind_ = Kind::Constant;
    float c_ = 1.0f;
    vec3 a_{0.0f}, b_{0.0f};  // Cauchy (A, B); Sellmeier B, C; per-channel η and λ
    SpectrumPtr spectrum_;
};

/// Named IOR presets as Mitsuba 3 documents them (dielectric plugin table; standard published
/// values at about 589 nm). Returns false for an unknown name.
bool lookupIORPreset(const std::string& name, float* eta);
/// All preset names (for error messages and docs).
std::vector<std::string> iorPresetNames();

/// Read an IOR parameter family from Properties (prefix "int" or "ext"):
///   <prefix>_ior              float | preset name | rgb (per-channel η_R, η_G, η_B) | spectrum (tabulated)
///   <prefix>_ior_wavelengths  vector (λ_R, λ_G, λ_B) nm for the per-channel form (default 645 525 445)
///   <prefix>_cauchy_a, <prefix>_cauchy_b         Cauchy coefficients (B in µm²)
///   <prefix>_sellmeier_b, <prefix>_sellmeier_c   Sellmeier B1..3 and C1..3 (µm²) as vectors
/// At most one form may be given; none gives `def` (a preset name or a number as text).
IOR readIOR(const Properties& p, const std::string& prefix, const std::string& def);


/// The relative index η_int/η_ext of a dielectric interface at the path's wavelengths, written
/// to *eta. When it varies with λ in spectral mode the secondary wavelengths are terminated
/// (wl.terminateSecondary(), pbrt-v4 §9.5.2). Returns the η that decides refracted directions:
/// the hero wavelength's (index 0) in spectral mode, the green channel's (index 1) in RGB mode.
float relativeIOR(const IOR& intIOR, const IOR& extIOR, SampledWavelengths& wl, SampledSpectrum* eta);

}  // namespace iris
