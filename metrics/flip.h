// FLIP, the perceptual difference evaluator of P. Andersson, J. Nilsson, T. Akenine-Möller,
// M. Oskarsson, K. Åström, M. D. Fairchild, "FLIP: A Difference Evaluator for Alternating Images",
// Proc. ACM Comput. Graph. Interact. Tech. 3(2), 15 (HPG 2020) — LDR-FLIP — and its HDR extension of
// P. Andersson, J. Nilsson, P. Shirley, T. Akenine-Möller, "Visualizing Errors in Rendered High
// Dynamic Range Images", Eurographics 2021 Short Papers — HDR-FLIP. Implemented from the papers;
// steps, constants and the validation are in docs/metrics.md ("FLIP").
#pragma once

#include <vector>

#include "core/io/image.h"

namespace iris {

namespace flip {

// Constants of the HPG 2020 paper (§4): colour-difference exponent q_c and remapping p_c, p_t
// (§4.1.3), feature width w in degrees and feature exponent q_f (§4.2).
constexpr double kQc = 0.7, kPc = 0.4, kPt = 0.95, kW = 0.082, kQf = 0.5;
// Spatial contrast sensitivity per opponent channel (achromatic, red-green, blue-yellow): the sum
// of Gaussians a1 e^{−b1 ρ²} + a2 e^{−b2 ρ²} in frequency (§4.1.1, Table 1).
struct CsfChannel {
    double a1, b1, a2, b2;
};
constexpr CsfChannel kCsf[3] = {{1.0, 0.0047, 0.0, 1e-5}, {1.0, 0.0053, 0.0, 1e-5}, {34.1, 0.04, 13.5, 0.025}};

/// Pixels per degree of visual angle, p = d (r / w) π / 180 for an observer at d metres from a
/// monitor w metres wide with r pixels per line (§5). Default viewing: 0.7 m, 0.7 m, 3840 px → 67.02.
double pixelsPerDegree(double distanceM = 0.7, double monitorWidthM = 0.7, double resolutionX = 3840);

/// Hunt-adjusted CIELAB (§4.1.2): L*, 0.01 L* a*, 0.01 L* b* of a linear Rec.709 triple.
void huntLab(double r, double g, double b, double out[3]);
/// HyAB distance |ΔL| + sqrt(Δa² + Δb²) (§4.1.3, after Abasi et al. 2020).
double hyab(const double x[3], const double y[3]);
/// c_max = HyAB(Hunt(green), Hunt(blue))^q_c, the largest colour distance in the gamut (§4.1.3).
double colorMax();
/// The colour error in [0,1] of a distance raised to q_c: linear on [0, p_c c_max) onto [0, p_t),
/// then linear onto [p_t, 1] (§4.1.3, Figure 4).
double remapColorError(double powered);

/// One-dimensional filters in pixels (index i ↔ offset i − radius). CSF Gaussian of one term,
/// e^{−π² (x/p)² / b}, unnormalised; radius ⌈3 sqrt(b_max / (2π²)) p⌉ with b_max the largest b of
/// kCsf (§4.1.1).
std::vector<double> csfGaussian(double b, double ppd);
int csfRadius(double ppd);
/// Feature filters, σ = ½ w p, radius ⌈3σ⌉ (§4.2.1): the Gaussian (sum 1), its first derivative
/// −x e^{−x²/2σ²} and second derivative (x²/σ² − 1) e^{−x²/2σ²}, each with its positive weights
/// scaled to sum 1 and its negative weights to sum −1, so a constant image gives 0.
struct FeatureFilters {
    std::vector<double> gauss, first, second;
};
FeatureFilters featureFilters(double ppd);

/// Tone mapper of HDR-FLIP: ACES filmic fit of K. Narkowicz (2015, "ACES Filmic Tone Mapping
/// Curve"), y(u) = u(2.51u + 0.03) / (u(2.43u + 0.59) + 0.14) at u = 0.6 x (the 0.6 cancels the
/// fit's pre-exposure, as in HDR-FLIP §2), clamped to [0,1].
double toneMapAces(double x);
/// The x ≥ 0 with toneMapAces(x) = t (0 < t < 1): the positive root of the quadratic
/// (t k3 − k0) x² + (t k4 − k1) x + t k5 − k2 = 0 (HDR-FLIP §2, "Computing start and stop exposures").
double inverseToneMapAces(double t);

}  // namespace flip

/// Exposure compensations c (stops) at which HDR-FLIP evaluates LDR-FLIP: c_start maps the
/// reference's largest luminance, c_stop its median luminance, to 0.85 after tone mapping;
/// count = max(2, ⌈c_stop − c_start⌉) values evenly spaced from c_start to c_stop.
struct FlipExposures {
    double start = 0, stop = 0;
    int count = 0;
};

struct FlipResult {
    Image map;            // one channel "FLIP", per-pixel error in [0,1] (NaN where an input is not finite)
    double mean = 0;      // mean over the finite pixels
    FlipExposures exposures;   // HDR-FLIP only
};

/// LDR-FLIP of linear Rec.709 images, each value clamped to [0,1] (the display's linear RGB, i.e.
/// the sRGB-encoded picture decoded). Colour channels are chosen as in compareImages (a grey
/// image is replicated). Pixels where either image is not finite are set to 0 for the filters and
/// excluded from the mean. Throws iris::Error for a size or channel-count mismatch.
FlipResult ldrFlip(const Image& test, const Image& ref, double ppd = flip::pixelsPerDegree());

/// HDR-FLIP: per pixel the maximum over the exposures of LDR-FLIP of toneMapAces(2^c · image)
/// (negative values clamped to 0 first).
FlipResult hdrFlip(const Image& test, const Image& ref, double ppd = flip::pixelsPerDegree());

/// The exposures of HDR-FLIP for a reference image (luminance Y = 0.2126 R + 0.7152 G + 0.0722 B
/// of the values clamped to ≥ 0; median = element ⌊n/2⌋ of the sorted finite luminances). Where
/// the median is 0 the smallest positive luminance stands in for it; an all-black reference gives
/// the single pair start = stop = 0.
FlipExposures hdrFlipExposures(const Image& ref);

}  // namespace iris
