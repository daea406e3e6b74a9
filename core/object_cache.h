// The objects a scene load creates from its parsed Properties, by Properties and type: a <bsdf>,
// <medium>, <texture> or <shapegroup> that several objects refer to (<ref id>) is created once and
// shared. The cache belongs to the load (ParsedScene holds it, every Properties of that parse points
// to it) and dies with it; the objects live on in the scene description. Entries are typed: an
// object stored as a Material is found only as a Material.
#pragma once

#include <map>
#include <memory>
#include <typeindex>
#include <utility>

namespace iris {

class Properties;

class ObjectCache {
public:
    /// The object of type T created from `p`, or nullptr.
    template <class T>
    std::shared_ptr<T> find(const Properties& p) const {
        const auto it = objects_.find(Key{&p, std::type_index(typeid(T))});
        return it == objects_.end() ? nullptr : std::static_pointer_cast<T>(it->second);
    }
    template <class T>
    void store(const Properties& p, std::shared_ptr<T> object) {
        objects_[Key{&p, std::type_index(typeid(T))}] = std::move(object);
    }

private:
    using Key = std::pair<const Properties*, std::type_index>;
    std::map<Key, std::shared_ptr<void>> objects_;
};

}  // namespace iris
