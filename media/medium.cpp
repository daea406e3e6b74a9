#include "media/medium.h"

#include "core/error.h"

namespace iris {

MediumCommon readMediumCommon(const Properties& p) {
    MediumCommon c;
    PropertiesPtr phase = p.getObject("phase", false);
    for (const PropertiesPtr& child : p.children()) {
        if (child->tag() != "phase")
            failAt(child->location(), "unexpected unnamed <", child->tag(), "> inside <medium> (allowed: phase; volumes and spectra need a name)");
        if (phase) failAt(child->location(), "medium has more than one <phase>");
        phase = child;
    }
    if (phase) {
        if (phase->tag() != "phase") failAt(p.locationOf("phase"), "parameter 'phase' must be a <phase>");
        c.phase = PhaseFunctionRegistry::instance().create(*phase);
    } else {
        c.phase = PhaseFunctionRegistry::instance().create(Properties("phase", "isotropic", p.location()));
    }
    c.sampleEmitters = p.getBool("sample_emitters", true);
    return c;
}

}  // namespace iris

namespace iris {

void checkMediumSpectrum(const Properties& p, const std::string& name, const Spectrum& s, float lo, float hi) {
    for (const SampledWavelengths& wl : parameterCheckWavelengths()) {
        const SampledSpectrum v = s.sample(wl);
        for (int k = 0; k < v.size(); ++k)
            if (!(v[k] >= lo && v[k] <= hi))
                failAt(p.locationOf(name), "<medium type=\"", p.type(), "\">: ", name, " = ", v[k], wl.isRGB() ? " in RGB channel " : " at ",
                       wl.isRGB() ? std::to_string(k) : std::to_string(int(wl.lambda(k))) + " nm",
                       hi >= 1e30f ? std::string(" is negative") : strCat(" is outside [", lo, ", ", hi, "]"));
    }
}

}  // namespace iris
