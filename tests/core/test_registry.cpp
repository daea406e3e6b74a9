// The plugin registry: a name registered twice is an error, an unknown type gives the one
// "file:line: unknown <tag> type 'x' (supported: ...)" message, and create() reports unread
// parameters.
#include <gtest/gtest.h>

#include "core/registry.h"

using namespace iris;

namespace {
struct Thing {
    int value = 0;
};
std::shared_ptr<Thing> makeThing(const Properties& p) {
    auto t = std::make_shared<Thing>();
    t->value = p.getInt("value", 1);
    return t;
}
}  // namespace

TEST(Registry, DuplicateNameIsAnError) {
    Registry<Thing> r;
    r.add("a", makeThing);
    r.add("b", makeThing);
    try {
        r.add("a", makeThing);
        FAIL() << "a duplicate name was accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("'a' is registered twice"), std::string::npos) << e.what();
    }
    EXPECT_EQ(r.names(), (std::vector<std::string>{"a", "b"}));
}

TEST(Registry, UnknownTypeNamesFileLineAndTheSupportedTypes) {
    Registry<Thing> r;
    r.add("box", makeThing);
    r.add("gaussian", makeThing);
    const Properties p("rfilter", "sinc", SourceLocation{"scene.xml", 12});
    try {
        r.create(p);
        FAIL() << "an unknown type was created";
    } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()), "scene.xml:12: unknown rfilter type 'sinc' (supported: box, gaussian)");
    }
}

TEST(Registry, CreateReadsParametersAndRejectsUnknownOnes) {
    Registry<Thing> r;
    r.add("t", makeThing);
    Properties p("thing", "t", SourceLocation{"scene.xml", 3});
    p.set("value", int64_t(7), SourceLocation{"scene.xml", 4});
    EXPECT_EQ(r.create(p)->value, 7);
    p.set("colour", 1.0f, SourceLocation{"scene.xml", 5});
    EXPECT_THROW(r.create(p), Error);
}
