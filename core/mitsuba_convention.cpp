#include "core/mitsuba_convention.h"

#include "core/error.h"
#include "core/properties.h"

namespace iris {

const char* conventionName(MitsubaConvention c) {
    return c == MitsubaConvention::Mitsuba06 ? "mitsuba0.6" : "mitsuba3";
}

MitsubaConvention getConvention(const Properties& p) {
    const std::string name = p.getString("convention", conventionName(MitsubaConvention::Mitsuba3));
    for (MitsubaConvention c : {MitsubaConvention::Mitsuba3, MitsubaConvention::Mitsuba06})
        if (name == conventionName(c)) return c;
    failAt(p.locationOf("convention"), p.tag(), " '", p.type(), "': unknown convention '", name,
           "' (known: mitsuba3, mitsuba0.6)");
}

}  // namespace iris
