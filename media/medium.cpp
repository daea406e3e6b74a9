#include "media/medium.h"

#include "core/error.h"
#include "media/volume_light.h"

namespace iris {

MediumCommon readMediumCommon(const Properties& p) {
    MediumCommon c;
    PropertiesPtr phase = p.getObject("phase", false), emitter = p.getObject("emitter", false);
    for (const PropertiesPtr& child : p.children()) {
        if (child->tag() == "emitter") {  // Mitsuba 3 Medium: one nested emitter, a volumelight
            if (emitter) failAt(child->location(), "medium has more than one <emitter> (Mitsuba 3: \"Only a single emitter can be specified per medium\")");
            emitter = child;
            continue;
        }
        if (child->tag() != "phase")
            failAt(child->location(), "unexpected unnamed <", child->tag(), "> inside <medium> (allowed: phase, emitter; volumes and spectra need a name)");
        if (phase) failAt(child->location(), "medium has more than one <phase>");
        phase = child;
    }
    if (emitter) {
        if (emitter->tag() != "emitter" || emitter->type() != "volumelight")
            failAt(emitter->location(), "a medium's emitter must be <emitter type=\"volumelight\">");
        c.emission = readVolumeLight(*emitter);
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

void Medium::setEmission(VolumePtr emission, const SourceLocation& where) {
    if (emission_) failAt(where, "this medium has an emitter already (Mitsuba 3: \"A medium can only have one emitter attached\")");
    emission_ = std::move(emission);
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
