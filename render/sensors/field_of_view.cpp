#include "render/sensors/field_of_view.h"

#include <cstdlib>

namespace iris {
namespace {

FovAxis parseFovAxis(const Properties& p) {
    const std::string axis = p.getString("fov_axis", "x");
    if (axis == "x") return FovAxis::X;
    if (axis == "y") return FovAxis::Y;
    if (axis == "diagonal") return FovAxis::Diagonal;
    if (axis == "smaller") return FovAxis::Smaller;
    if (axis == "larger") return FovAxis::Larger;
    failAt(p.locationOf("fov_axis"), "fov_axis '", axis, "' is not one of x, y, diagonal, smaller, larger");
}

/// A focal length "50mm" (or "50") in 35 mm-film-equivalent millimetres.
float parseFocalLength(const Properties& p) {
    std::string f = p.getString("focal_length", "50mm");
    if (f.size() > 2 && f.compare(f.size() - 2, 2, "mm") == 0) f.resize(f.size() - 2);
    char* end = nullptr;
    const float v = std::strtof(f.c_str(), &end);
    if (f.empty() || end != f.c_str() + f.size() || !(v > 0) || !std::isfinite(v))
        failAt(p.locationOf("focal_length"), "focal_length '", p.getString("focal_length"), "' must be a positive length like \"50mm\"");
    return v;
}

}  // namespace

FieldOfView parseFieldOfView(const Properties& p) {
    // Mitsuba 3 (src/render/sensor.cpp, parse_fov) and 0.6 alike: `fov` along `fov_axis` (default
    // x), or else `focal_length` (0.6: focalLength; default 50 mm) on a 36 × 24 mm film measured
    // along its diagonal, fov = 2 atan(√(36² + 24²) / (2 f)) (46.79° for 50 mm), fov_axis ignored.
    FieldOfView fov;
    if (p.has("fov")) {
        if (p.has("focal_length")) failAt(p.locationOf("focal_length"), "give either fov or focal_length, not both");
        fov.degrees = p.getFloat("fov");
        if (!(fov.degrees > 0 && fov.degrees < 180)) failAt(p.locationOf("fov"), "fov must be in (0, 180) degrees");
        fov.axis = parseFovAxis(p);
    } else {
        const float f = parseFocalLength(p);
        fov.degrees = 2.0f * std::atan(std::sqrt(36.0f * 36.0f + 24.0f * 24.0f) / (2.0f * f)) * 180.0f / kPi;
        fov.axis = FovAxis::Diagonal;
        p.getString("fov_axis", "x");  // accepted; Mitsuba ignores it with a focal length
    }
    return fov;
}

vec2 tanHalfAngles(const FieldOfView& fov, float aspect) {
    const float t = std::tan(glm::radians(fov.degrees) * 0.5f);
    FovAxis axis = fov.axis;
    if (axis == FovAxis::Smaller) axis = aspect > 1 ? FovAxis::Y : FovAxis::X;
    if (axis == FovAxis::Larger) axis = aspect > 1 ? FovAxis::X : FovAxis::Y;
    switch (axis) {
        case FovAxis::X: return vec2(t, t / aspect);
        case FovAxis::Y: return vec2(t * aspect, t);
        default: {  // diagonal: t is the half-diagonal's tangent
            const float diag = std::sqrt(aspect * aspect + 1.0f);
            return vec2(t * aspect / diag, t / diag);
        }
    }
}

}  // namespace iris
