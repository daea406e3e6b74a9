// The materials nested in a wrapper bsdf (normalmap, bumpmap, blendbsdf, ...), Mitsuba style:
// unnamed <bsdf> children in document order, then <bsdf> objects under parameter names that are
// not the wrapper's own, by name. Each is created once and cached in its Properties::instance like
// every other scene object, so a referenced bsdf is shared. Errors name the wrapper's location.
#pragma once

#include <set>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/registry.h"
#include "materials/material.h"

namespace iris {

/// The nested object under parameter `name` of a wrapper; any other value there is an unknown
/// parameter of the wrapper (error naming it and the known ones).
inline PropertiesPtr nestedObjectOrFail(const Properties& p, const std::string& name, const std::string& plugin,
                                        const std::set<std::string>& ownParams) {
    try {
        return p.getObject(name);
    } catch (const Error&) {
        std::string known;
        for (const auto& k : ownParams) known += (known.empty() ? "" : ", ") + k;
        failAt(p.locationOf(name), "unknown parameter '", name, "' of bsdf '", plugin, "' (known parameters: ", known,
               ", and nested objects)");
    }
}

/// Every bsdf nested in wrapper `plugin` (see the file comment), created or taken from the cache.
/// Properties::names() is sorted, so named ones come in the alphanumeric order of their names, as
/// Mitsuba 3 assigns them (blendbsdf: "based on the alphanumeric order of their identifiers").
inline std::vector<std::shared_ptr<Material>> createNestedMaterials(const Properties& p, const std::string& plugin,
                                                                   const std::set<std::string>& ownParams) {
    std::vector<PropertiesPtr> nested;
    for (const PropertiesPtr& c : p.children())
        if (c->tag() == "bsdf") nested.push_back(c);   // other children (textures) are the wrapper's
    for (const std::string& name : p.names()) {
        if (ownParams.count(name)) continue;
        const PropertiesPtr obj = nestedObjectOrFail(p, name, plugin, ownParams);
        if (obj->tag() == "bsdf") nested.push_back(obj);
    }
    std::vector<std::shared_ptr<Material>> out;
    for (const PropertiesPtr& child : nested)
        out.push_back(cachedObject<Material>(*child, [&] { return MaterialRegistry::instance().create(*child); }));
    return out;
}

/// The one material nested in a wrapper `plugin`.
inline std::shared_ptr<Material> createNestedMaterial(const Properties& p, const std::string& plugin,
                                                     const std::set<std::string>& ownParams) {
    auto nested = createNestedMaterials(p, plugin, ownParams);
    if (nested.size() != 1) failAt(p.location(), plugin, ": expected exactly one nested bsdf, got ", nested.size());
    return nested[0];
}

}  // namespace iris
