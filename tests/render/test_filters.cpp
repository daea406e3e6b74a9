// Reconstruction filters: Mitsuba's profiles at known values, their defaults, and filter importance
// sampling: E[weight] = 1 and E[weight · x²] = ∫ x² f / ∫ f (the normalised filter), also for the
// negative lobes of mitchell, catmullrom and lanczos.
#include <gtest/gtest.h>

#include "core/rng.h"
#include "render/filters/rfilter.h"

using namespace iris;

namespace {

ReconstructionFilterPtr filterWith(const std::string& type, const std::string& name = "", float value = 0) {
    Properties p("rfilter", type, SourceLocation{"f.xml", 1});
    if (!name.empty()) {
        if (name == "lobes") p.set(name, int64_t(value), SourceLocation{"f.xml", 2});
        else p.set(name, value, SourceLocation{"f.xml", 2});
    }
    return RFilterRegistry::instance().create(p);
}

/// ∫ x^k f(x) dx over the support (midpoint rule, 20000 steps).
double moment(const ReconstructionFilter& f, int k) {
    const int n = 20000;
    const double r = f.radius(), h = 2 * r / n;
    double s = 0;
    for (int i = 0; i < n; ++i) {
        const double x = -r + (i + 0.5) * h;
        s += std::pow(x, k) * f.eval(float(x)) * h;
    }
    return s;
}

/// Mean weight and mean weight · x² of n filter samples (fixed seed), with their standard errors.
struct Estimate {
    double w, wx2, seW, seWx2;
};
Estimate sampleMoments(const ReconstructionFilter& f, int n) {
    Pcg32 rng(11, 3);
    double s1 = 0, s1q = 0, s2 = 0, s2q = 0;
    for (int i = 0; i < n; ++i) {
        const FilterSample fs = f.sample(vec2(rng.uniform(), rng.uniform()));
        EXPECT_LE(std::abs(fs.offset.x), f.radius() + 1e-5f);
        const double a = fs.weight, b = fs.weight * double(fs.offset.x) * fs.offset.x;
        s1 += a, s1q += a * a, s2 += b, s2q += b * b;
    }
    const double m1 = s1 / n, m2 = s2 / n;
    return {m1, m2, std::sqrt((s1q / n - m1 * m1) / n), std::sqrt((s2q / n - m2 * m2) / n)};
}

}  // namespace

TEST(Filters, ProfilesAtKnownValues) {
    const auto tent = filterWith("tent");
    EXPECT_FLOAT_EQ(tent->radius(), 1.0f);
    EXPECT_FLOAT_EQ(tent->eval(0.25f), 0.75f);
    EXPECT_FLOAT_EQ(filterWith("tent", "radius", 2.0f)->eval(1.0f), 0.5f);
    const auto mitchell = filterWith("mitchell");  // B = C = 1/3, radius 2
    EXPECT_FLOAT_EQ(mitchell->radius(), 2.0f);
    EXPECT_NEAR(mitchell->eval(0.0f), 16.0 / 18.0, 1e-6);   // (6 − 2B) / 6
    EXPECT_NEAR(mitchell->eval(1.0f), 1.0 / 18.0, 1e-6);    // (8B + 24C − 12B − 48C + 6B + 30C − B − 6C) / 6 = B/6
    EXPECT_LT(mitchell->eval(1.5f), 0.0f);                   // the negative lobe
    const auto catmull = filterWith("catmullrom");           // B = 0, C = 1/2: interpolating
    EXPECT_NEAR(catmull->eval(0.0f), 1.0, 1e-6);
    EXPECT_NEAR(catmull->eval(1.0f), 0.0, 1e-6);
    const auto lanczos = filterWith("lanczos");  // lobes 3 = radius
    EXPECT_FLOAT_EQ(lanczos->radius(), 3.0f);
    EXPECT_NEAR(lanczos->eval(0.0f), 1.0, 1e-6);
    EXPECT_NEAR(lanczos->eval(1.0f), 0.0, 1e-6);
    EXPECT_NEAR(lanczos->eval(0.5f), 0.5 / (M_PI * M_PI * 0.25 / 3.0), 1e-5);  // sin(π/2) sin(π/6) / (π² x² / 3)
    EXPECT_FLOAT_EQ(filterWith("lanczos", "lobes", 2)->radius(), 2.0f);
}

TEST(Filters, NormalisedIntegralsOfTheProfiles) {
    EXPECT_NEAR(moment(*filterWith("tent"), 0), 1.0, 1e-6);       // ∫ tent = r
    EXPECT_NEAR(moment(*filterWith("mitchell"), 0), 1.0, 1e-6);   // Mitchell–Netravali kernels integrate to 1
    EXPECT_NEAR(moment(*filterWith("catmullrom"), 0), 1.0, 1e-6);
    EXPECT_NEAR(moment(*filterWith("box"), 0), 1.0, 1e-3);        // radius 0.5
}

TEST(Filters, ImportanceSamplingReproducesTheNormalisedFilter) {
    for (const char* type : {"box", "gaussian", "tent", "mitchell", "catmullrom", "lanczos"}) {
        SCOPED_TRACE(type);
        const ReconstructionFilterPtr f = filterWith(type);
        const Estimate e = sampleMoments(*f, 200000);
        // Mean weight 1 (exactly 1 per sample for filters without negative lobes), and the second
        // moment of the normalised 1D filter (the y axis integrates to 1). Tolerance: 5 standard
        // errors plus the 1024-segment tabulation (≤ 1e-3 relative).
        EXPECT_NEAR(e.w, 1.0, 5 * e.seW + 1e-9);
        const double expected = moment(*f, 2) / moment(*f, 0);
        EXPECT_NEAR(e.wx2, expected, 5 * e.seWx2 + 1e-3 * std::abs(expected)) << "expected " << expected;
    }
}

TEST(Filters, BadParametersAreRejected) {
    EXPECT_THROW(filterWith("tent", "radius", -1.0f), Error);
    EXPECT_THROW(filterWith("lanczos", "lobes", 0), Error);
    EXPECT_THROW(filterWith("mitchell", "radius", 2.0f), Error);  // Mitsuba's mitchell has no radius
}
