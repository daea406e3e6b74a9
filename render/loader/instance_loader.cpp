#include "render/loader/instance_loader.h"

#include <cmath>

#include "render/loader/shape_loader.h"

namespace iris {

namespace {

/// Every nested object of `p`: the unnamed children and the named ones.
std::vector<PropertiesPtr> nestedObjects(const Properties& p) {
    std::vector<PropertiesPtr> all = p.children();
    for (const std::string& name : p.names())
        if (p.peekObject(name)) all.push_back(p.getObject(name));
    return all;
}

/// The group's id, or "shapegroup" for one nested in an instance without an id (for messages).
std::string groupName(const Properties& group) { return !group.id().empty() ? group.id() : "shapegroup"; }

/// Mitsuba 3's ShapeGroup constructor refuses nested instancing, nested groups and emitters
/// ("Nested instancing is not permitted", "Instancing of emitters is not supported").
void checkGroupMember(const Properties& group, const Properties& member) {
    const std::string where = strCat(" (in shapegroup '", groupName(group), "' at ", group.location().str(), ")");
    if (member.tag() != "shape")
        failAt(member.location(), "a shapegroup holds only shapes, not a <", member.tag(), ">", where);
    if (member.type() == "shapegroup")
        failAt(member.location(), "a shapegroup cannot contain another shapegroup (nested instancing is not permitted, as in Mitsuba 3)", where);
    if (member.type() == "instance")
        failAt(member.location(), "a shapegroup cannot contain an instance (nested instancing is not permitted, as in Mitsuba 3)", where);
}

void checkNoEmitter(const Properties& member, const ShapeDescription& s, const std::string& groupId) {
    if (s.emission || s.emissionTexture)
        failAt(member.location(), "shape '", s.name, "' in shapegroup '", groupId, "' has an area emitter: instancing of emitters is "
               "not supported (as in Mitsuba 3); place the emitting shape outside the group");
}

std::shared_ptr<ShapeGroupDescription> buildGroup(const Properties& p) {
    auto g = std::make_shared<ShapeGroupDescription>();
    g->name = groupName(p);
    for (const PropertiesPtr& member : nestedObjects(p)) {
        checkGroupMember(p, *member);
        ShapeDescription s = loadShape(*member);
        checkNoEmitter(*member, s, g->name);
        g->shapes.push_back(std::move(s));
    }
    p.checkUnqueried();
    return g;
}

/// The one shapegroup an instance names (Mitsuba 3, Instance's constructor: "Only a shapegroup can
/// be specified in an instance", "A reference to a 'shapegroup' must be specified!").
const Properties& instancedGroup(const Properties& p) {
    const Properties* group = nullptr;
    for (const PropertiesPtr& obj : nestedObjects(p)) {
        if (obj->tag() != "shape" || obj->type() != "shapegroup")
            failAt(p.location(), "an instance refers only to a shapegroup, but this one holds <", obj->tag(), " type=\"", obj->type(),
                   "\"", obj->id().empty() ? std::string() : " id=\"" + obj->id() + "\"", "> (defined at ", obj->location().str(), ")");
        if (group) failAt(p.location(), "an instance refers to exactly one shapegroup, this one to more");
        group = obj.get();
    }
    if (!group) failAt(p.location(), "an instance needs a shapegroup: add <ref id=\"...\"/> naming a <shape type=\"shapegroup\">");
    return *group;
}

}  // namespace

std::shared_ptr<const ShapeGroupDescription> loadShapeGroup(const Properties& p) {
    return cachedObject<ShapeGroupDescription>(p, [&] { return buildGroup(p); });
}

InstanceDescription loadInstance(const Properties& p) {
    const Properties& group = instancedGroup(p);
    InstanceDescription inst;
    inst.toWorld = p.getTransform("to_world");
    const float det = glm::determinant(mat3(inst.toWorld));
    if (!(std::abs(det) > 1e-30f) || !std::isfinite(det))
        failAt(p.locationOf("to_world"), "the instance's to_world is not invertible (determinant ", det, "): rays cannot be carried into the group");
    inst.group = loadShapeGroup(group);
    inst.name = strCat("instance of '", inst.group->name, "' at ", p.location().str());
    p.checkUnqueried();
    return inst;
}

}  // namespace iris
