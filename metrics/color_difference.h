// Colour differences for image comparison: linear Rec.709 RGB → CIE XYZ (D65) → CIELAB, and the
// CIEDE2000 colour difference. Used only by metrics, never for image output.
#pragma once

namespace iris {

struct Lab {
    double L = 0, a = 0, b = 0;
};

/// CIE XYZ (D65, white Y = 1) of a linear Rec.709 / sRGB-primaries RGB triple (IEC 61966-2-1 matrix).
void linearRec709ToXYZ(double r, double g, double b, double xyz[3]);
/// Linear Rec.709 of a CIE XYZ triple: the inverse of linearRec709ToXYZ's matrix (computed from it).
void xyzToLinearRec709(const double xyz[3], double rgb[3]);
/// XYZ of the RGB white (1,1,1): the reference white of every Lab conversion here (D65, Y = 1).
void rec709WhiteXYZ(double xyz[3]);
/// CIELAB (CIE 15:2004 §8.2.1) of a linear Rec.709 triple, with reference white = the RGB white
/// (1,1,1) (D65, Y = 1). Values are not clamped: HDR values give L* > 100.
Lab linearRec709ToLab(double r, double g, double b);
/// CIEDE2000 colour difference ΔE00 with kL = kC = kH = 1 (Sharma, Wu, Dalal 2005, eqs. 1–17).
double ciede2000(const Lab& x, const Lab& y);

}  // namespace iris
