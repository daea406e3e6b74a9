#include "media/volume_light.h"

#include "core/error.h"

namespace iris {

VolumePtr readVolumeLight(const Properties& emitter) {
    if (emitter.has("to_world"))
        failAt(emitter.locationOf("to_world"), "volumelight: a 'to_world' transformation is not allowed (the light inherits "
                                                "its shape's; Mitsuba 3 refuses it too)");
    VolumePtr j = getVolume(emitter, "radiance", SpectrumKind::Unbounded, 0.0f);
    if (j->range().min < 0.0f)
        failAt(emitter.locationOf("radiance"), "volumelight: radiance has negative values (minimum ", j->range().min, ")");
    emitter.checkUnqueried();
    return j;
}

}  // namespace iris
