// First stage of scene loading: a Mitsuba XML file (0.6 or 2.x/3.x syntax) becomes a list of
// Properties trees, one per top-level object, with includes inlined, $parameters substituted,
// <ref>s resolved to the referenced (shared) Properties, every "filename" resolved to an absolute
// path and every object marked with its file's major version (an unsupported version is refused
// here, with file and line). Names and values are as written: the version rules and the defaults
// are applied afterwards by render/loader/scene_upgrade.h. docs/scene_format.md describes the format.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "core/properties.h"

namespace iris {

struct ParsedScene {
    std::string sourceFile;               // the main file (or "<string>")
    std::vector<PropertiesPtr> objects;   // top-level objects in document order
    /// The objects the loader creates from these Properties (every Properties of the parse points
    /// to it): a <ref>erenced object is created once. Lives as long as the parse result.
    std::shared_ptr<ObjectCache> cache = std::make_shared<ObjectCache>();
};

/// Parse a scene file; `defines` override its <default> values (like mitsuba -D name=value).
ParsedScene parseSceneFile(const std::string& path, const std::map<std::string, std::string>& defines = {});
/// Parse scene XML held in memory; relative paths are resolved against `baseDir`.
ParsedScene parseSceneString(const std::string& xml, const std::string& baseDir,
                             const std::map<std::string, std::string>& defines = {});

}  // namespace iris
