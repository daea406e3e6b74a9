#include "spectral/color_space.h"

#include "spectral/cie.h"
#include "spectral/xyz.h"

namespace iris {

dvec3 xyzToLinearRec709(const dvec3& c) {
    // IEC 61966-2-1:1999 (sRGB), eq. (5); the 4-digit matrix published in the standard.
    return dvec3(3.2406 * c.x - 1.5372 * c.y - 0.4986 * c.z,
                 -0.9689 * c.x + 1.8758 * c.y + 0.0415 * c.z,
                 0.0557 * c.x - 0.2040 * c.y + 1.0570 * c.z);
}

dvec3 linearRec709ToXYZ(const dvec3& c) {
    // IEC 61966-2-1:1999 (sRGB), eq. (7).
    return dvec3(0.4124 * c.x + 0.3576 * c.y + 0.1805 * c.z,
                 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z,
                 0.0193 * c.x + 0.1192 * c.y + 0.9505 * c.z);
}

double d65YNormalisation() {
    static const double k = 1.0 / integrateXYZ([](float l) { return cie::d65(l); }).y;
    return k;
}

const dvec3* reflectanceRGBWeights() {
    struct Table {
        dvec3 w[kReflectanceWeightCount];
        Table() {
            static_assert(kReflectanceWeightCount == cie::kQuadratureLast - cie::kQuadratureFirst + 1);
            double ySum = 0;
            for (int i = 0; i < kReflectanceWeightCount; ++i) {
                const float l = float(cie::kQuadratureFirst + i);
                ySum += double(cie::d65(l)) * cie::yBar(l);
            }
            for (int i = 0; i < kReflectanceWeightCount; ++i) {
                const float l = float(cie::kQuadratureFirst + i);
                w[i] = xyzToLinearRec709(double(cie::d65(l)) * dvec3(cie::xyzBar(l)) / ySum);
            }
        }
    };
    static const Table table;
    return table.w;
}

vec3 rgbProjection(const std::function<float(float)>& f, SpectrumKind kind) {
    switch (kind) {
        case SpectrumKind::Reflectance: {
            const dvec3* w = reflectanceRGBWeights();
            dvec3 rgb(0.0);
            for (int i = 0; i < kReflectanceWeightCount; ++i)
                rgb += double(f(float(cie::kQuadratureFirst + i))) * w[i];
            return vec3(rgb);
        }
        case SpectrumKind::Illuminant:
            return vec3(xyzToLinearRec709(integrateXYZ(f)));
        case SpectrumKind::Unbounded:
        default: {
            const vec3 l = defaultChannelWavelengths();
            return vec3(f(l.x), f(l.y), f(l.z));
        }
    }
}

}  // namespace iris
