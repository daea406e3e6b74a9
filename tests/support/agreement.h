// Agreement of two renders of one scene by two estimators (light tracing against path tracing):
// Welch's statistic on block means (Jung, Hanika & Dachsbacher, JCGT 9(2), 2020; as
// experiments/conformance/welch.py), with the normal quantile since every pixel holds hundreds of
// samples. Each film's per-pixel variance of the mean is its own estimate s²/n (Film::
// varianceOfMeanImage); a block of k×k pixels has the mean of its pixel means and the variance
// Σ v / k⁴. Blocks rather than pixels: a light tracer's pixel is a sum of few splats per pass,
// skewed where few light paths reach it, and block means are close to normal where single pixels
// are not. Tested: every k×k block and the whole image, every channel, at a Šidák-corrected level.
#pragma once

#include <string>

#include "render/film.h"

namespace iris::test {

struct Agreement {
    double maxAbsZ = 0;     // the largest |z| over all tests
    double threshold = 0;   // the two-sided normal quantile at the corrected level
    int tests = 0;
    std::string where;      // the block and channel of maxAbsZ, with both means
    bool passed() const { return maxAbsZ < threshold; }
};

/// Blocks of `block`×`block` pixels (and the whole image) of `test` against `ref`, significance
/// `alpha` over all tests (Šidák). Blocks with zero variance on both sides and equal means pass.
/// The default level, 10⁻³ for the family of one comparison, allows for the variance a light tracer
/// underestimates where few large splats make a block's distribution skewed (measured on the
/// directional-light scene: the largest |z| of equal estimators reached 3.7 over 51 tests).
Agreement compareFilms(const Film& test, const Film& ref, int block = 4, double alpha = 1e-3);

/// The same over the pixels [x0, x1) × [y0, y1) only (blocks inside it, and the whole of it).
struct PixelRect {
    int x0, y0, x1, y1;
};
Agreement compareFilms(const Film& test, const Film& ref, const PixelRect& rect, int block = 4, double alpha = 1e-3);

/// The two-sided standard normal quantile z with P(|Z| > z) = p.
double normalQuantileTwoSided(double p);

}  // namespace iris::test
