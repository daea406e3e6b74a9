#include "render/scene.h"

#include <embree3/rtcore.h>

#include <map>

#include "core/error.h"
#include "render/lights/area_light.h"
#include "core/properties.h"
#include "core/registry.h"
#include "materials/material.h"
#include "core/cylinder_intersection.h"
#include "core/sdf_grid_intersection.h"
#include "core/sphere_intersection.h"
#include "render/instance_transform.h"
#include "render/scene_memory.h"
#include "render/scene_defaults.h"

namespace iris {

struct Scene::ShapeData {
    const ShapeDescription* desc = nullptr;
    const Material* material = nullptr;
    const Light* areaLight = nullptr;
};

namespace {
void embreeError(void*, RTCError code, const char* str) {
    // Errors during building are checked through rtcGetDeviceError; this only keeps Embree quiet.
    (void)code;
    (void)str;
}

// The analytic shapes (spheres, cylinders) are Embree user geometry, one primitive each, and an SDF
// grid one primitive per surface voxel, intersected in double precision (core/sphere_intersection.h,
// core/cylinder_intersection.h, core/sdf_grid_intersection.h).
// The scene only calls rtcIntersect1 and rtcOccluded1, so Embree calls these with one ray (N = 1).
// Scene::intersect computes the surface interaction from the hit point; Ng is only a placeholder.
struct SphereShape {
    static unsigned count(const ShapeDescription&) { return 1; }
    static double hit(const ShapeDescription& s, unsigned, const RTCRay& r) {
        return intersectSphere(dvec3(r.org_x, r.org_y, r.org_z), dvec3(r.dir_x, r.dir_y, r.dir_z), dvec3(s.center),
                               double(s.radius), double(r.tnear), double(r.tfar));
    }
    static void bounds(const ShapeDescription& s, unsigned, vec3& lo, vec3& hi) {
        lo = s.center - vec3(s.radius);
        hi = s.center + vec3(s.radius);
    }
};

struct CylinderShape {
    static unsigned count(const ShapeDescription&) { return 1; }
    static double hit(const ShapeDescription& s, unsigned, const RTCRay& r) {
        return intersectCylinder(dvec3(r.org_x, r.org_y, r.org_z), dvec3(r.dir_x, r.dir_y, r.dir_z), s.cylinder,
                                 double(s.radius), double(r.tnear), double(r.tfar));
    }
    /// The two end circles' bounding boxes: a circle of radius r around the unit axis a extends
    /// r·sqrt(1 − a_i²) along world axis i.
    static void bounds(const ShapeDescription& s, unsigned, vec3& lo, vec3& hi) {
        const CylinderGeometry& c = s.cylinder;
        const vec3 p1 = c.p0 + c.length * c.axis;
        const vec3 e = s.radius * glm::sqrt(glm::max(vec3(0.0f), vec3(1.0f) - c.axis * c.axis));
        lo = glm::min(c.p0, p1) - e;
        hi = glm::max(c.p0, p1) + e;
    }
};

struct SdfGridShape {
    static unsigned count(const ShapeDescription& s) { return unsigned(s.sdf->voxels.size()); }
    static double hit(const ShapeDescription& s, unsigned prim, const RTCRay& r) {
        return intersectSdfVoxel(*s.sdf, prim, dvec3(r.org_x, r.org_y, r.org_z), dvec3(r.dir_x, r.dir_y, r.dir_z),
                                 double(r.tnear), double(r.tfar));
    }
    static void bounds(const ShapeDescription& s, unsigned prim, vec3& lo, vec3& hi) { s.sdf->voxelBounds(prim, lo, hi); }
};

template <class G>
void userBounds(const RTCBoundsFunctionArguments* args) {
    const auto& s = *static_cast<const ShapeDescription*>(args->geometryUserPtr);
    vec3 lo, hi;
    G::bounds(s, args->primID, lo, hi);
    // Padded by a few float ulps of the extent so that rounding the bounds to float never clips.
    const vec3 m = glm::max(glm::abs(lo), glm::abs(hi));
    const float pad = 1e-6f * (glm::length(hi - lo) + std::max({m.x, m.y, m.z}));
    RTCBounds* b = args->bounds_o;
    b->lower_x = lo.x - pad;
    b->lower_y = lo.y - pad;
    b->lower_z = lo.z - pad;
    b->upper_x = hi.x + pad;
    b->upper_y = hi.y + pad;
    b->upper_z = hi.z + pad;
}

template <class G>
void userIntersect(const RTCIntersectFunctionNArguments* args) {
    if (args->N != 1 || !args->valid[0]) return;
    const auto& s = *static_cast<const ShapeDescription*>(args->geometryUserPtr);
    RTCRayHit& rh = *reinterpret_cast<RTCRayHit*>(args->rayhit);
    const double t = G::hit(s, args->primID, rh.ray);
    if (!std::isfinite(t)) return;
    rh.ray.tfar = float(t);  // ≤ the old tfar: rounding is monotone and the old tfar is a float
    rh.hit.Ng_x = rh.hit.Ng_y = 0.0f;
    rh.hit.Ng_z = 1.0f;
    rh.hit.u = rh.hit.v = 0.0f;
    rh.hit.primID = args->primID;
    rh.hit.geomID = args->geomID;
    rh.hit.instID[0] = args->context->instID[0];
}

template <class G>
void userOccluded(const RTCOccludedFunctionNArguments* args) {
    if (args->N != 1 || !args->valid[0]) return;
    const auto& s = *static_cast<const ShapeDescription*>(args->geometryUserPtr);
    RTCRay& r = *reinterpret_cast<RTCRay*>(args->ray);
    if (std::isfinite(G::hit(s, args->primID, r))) r.tfar = -std::numeric_limits<float>::infinity();
}

void growBounds(vec3& lo, vec3& hi, const vec3& p) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
}

template <class G>
RTCGeometry userGeometry(RTCDevice device, const ShapeDescription& s, vec3& lo, vec3& hi) {
    RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
    rtcSetGeometryUserPrimitiveCount(geom, G::count(s));
    rtcSetGeometryUserData(geom, const_cast<ShapeDescription*>(&s));
    rtcSetGeometryBoundsFunction(geom, userBounds<G>, nullptr);
    rtcSetGeometryIntersectFunction(geom, userIntersect<G>);
    rtcSetGeometryOccludedFunction(geom, userOccluded<G>);
    for (unsigned prim = 0; prim < G::count(s); ++prim) {
        vec3 l, h;
        G::bounds(s, prim, l, h);
        growBounds(lo, hi, l);
        growBounds(lo, hi, h);
    }
    return geom;
}

void checkDevice(RTCDevice device, const char* what) {
    const RTCError err = rtcGetDeviceError(device);
    if (err != RTC_ERROR_NONE) fail("Embree error ", int(err), " while ", what);
}

/// The Embree geometry of one shape in its own space (world space for top-level shapes, the group's
/// space for shapes of a shape group), its bounds added to [lo, hi] and its triangles to
/// `triangles`; nullptr for a mesh without triangles.
RTCGeometry shapeGeometry(RTCDevice device, const ShapeDescription& s, vec3& lo, vec3& hi, size_t& triangles) {
    if (s.type == ShapeDescription::Type::Mesh) {
        if (!s.mesh) fail("shape '", s.name, "' has no mesh");
        const TriangleMesh& m = *s.mesh;
        m.validate();
        if (m.triangleCount() == 0) return nullptr;
        RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
        rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, m.positions.data(), 0, sizeof(vec3),
                                   m.positions.size());
        rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, m.indices.data(), 0, 3 * sizeof(uint32_t),
                                   m.triangleCount());
        triangles += m.triangleCount();
        for (const vec3& p : m.positions) growBounds(lo, hi, p);
        return geom;
    }
    if (s.type == ShapeDescription::Type::Sphere) {
        if (!(s.radius > 0) || !isFinite(s.center)) fail("sphere '", s.name, "' has an invalid radius or center");
        return userGeometry<SphereShape>(device, s, lo, hi);
    }
    if (s.type == ShapeDescription::Type::SdfGrid) {
        if (!s.sdf || s.sdf->voxels.empty()) fail("sdfgrid '", s.name, "' has no surface voxels");
        return userGeometry<SdfGridShape>(device, s, lo, hi);
    }
    const CylinderGeometry& c = s.cylinder;
    if (!(s.radius > 0) || !(c.length > 0) || !isFinite(c.p0) || !isFinite(c.axis))
        fail("cylinder '", s.name, "' has an invalid radius, length or position");
    return userGeometry<CylinderShape>(device, s, lo, hi);
}

/// The area light of an emitting top-level shape.
LightPtr areaLightOf(const ShapeDescription& s) {
    const SpectrumTexturePtr radiance =
        s.emissionTexture ? s.emissionTexture : std::make_shared<ConstantSpectrumTexture>(s.emission);
    if (s.type == ShapeDescription::Type::Mesh) return std::make_shared<AreaLight>(s.mesh.get(), radiance);
    if (s.type == ShapeDescription::Type::Sphere) return std::make_shared<AreaLight>(s.center, s.radius, s.frame, s.flipNormals, radiance);
    if (s.type == ShapeDescription::Type::SdfGrid) fail("sdfgrid '", s.name, "' cannot be an area emitter (as in Mitsuba 3)");
    return std::make_shared<AreaLight>(s.cylinder, s.radius, s.flipNormals, radiance);
}

void attachGeometry(RTCScene scene, RTCGeometry geom, unsigned id) {
    rtcCommitGeometry(geom);
    rtcAttachGeometryByID(scene, geom, id);
    rtcReleaseGeometry(geom);
}
}  // namespace

/// A placed shape group: its transform and where its shapes start in shapes_.
struct Scene::InstanceData {
    InstanceTransform transform;
    size_t firstShape;
};

Scene::Scene(SceneDescription desc) : desc_(std::move(desc)) {
    geometryMemory_ = chargeSceneGeometry(desc_);  // before Embree allocates (render/scene_memory.h)
    RTCDevice device = rtcNewDevice("verbose=0");
    if (!device) fail("cannot create the Embree device (error ", int(rtcGetDeviceError(nullptr)), ")");
    rtcSetDeviceErrorFunction(device, embreeError, nullptr);
    device_ = device;
    RTCScene scene = rtcNewScene(device);
    rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_HIGH);
    scene_ = scene;

    {
        Properties p("bsdf", kDefaultMaterial, SourceLocation{"<default material>", 0});
        defaultMaterial_ = MaterialRegistry::instance().create(p);
    }

    // A few top-level spheres and cylinders are tested one after the other outside Embree (issue
    // 37): the same double-precision test with the same ray bounds as Embree's callbacks, so the
    // closest hit is the same (up to exact ties in float t, which Embree breaks by its traversal
    // order), without a second BVH for user geometry and a callback per candidate.
    size_t analytic = 0;
    for (const ShapeDescription& s : desc_.shapes)
        analytic += s.type == ShapeDescription::Type::Sphere || s.type == ShapeDescription::Type::Cylinder;
    const bool flatAnalytic = analytic <= kMaxFlatShapes;

    vec3 lo(std::numeric_limits<float>::infinity()), hi(-std::numeric_limits<float>::infinity());
    for (size_t i = 0; i < desc_.shapes.size(); ++i) {
        const ShapeDescription& s = desc_.shapes[i];
        addShapeData(s);
        RTCGeometry geom = shapeGeometry(device, s, lo, hi, triangles_);
        if (!geom) continue;
        if (s.emission || s.emissionTexture) {
            lights_.push_back(areaLightOf(s));
            shapes_[i].areaLight = lights_.back().get();
        }
        if (flatAnalytic && (s.type == ShapeDescription::Type::Sphere || s.type == ShapeDescription::Type::Cylinder)) {
            rtcReleaseGeometry(geom);  // built for its checks and bounds only
            flat_.push_back(FlatShape{unsigned(i), s.type == ShapeDescription::Type::Cylinder});
            continue;
        }
        attachGeometry(scene, geom, unsigned(i));
        embreeGeometries_ = true;
        checkDevice(device, "building the scene geometry");
    }
    addInstances(lo, hi);
    embreeGeometries_ = embreeGeometries_ || !desc_.instances.empty();
    rtcCommitScene(scene);
    checkDevice(device, "building the acceleration structure");

    if (lo.x <= hi.x) {
        bounds_.center = 0.5f * (lo + hi);
        bounds_.radius = std::max(1e-3f, 0.5f * glm::length(hi - lo));
    }
    for (const LightPtr& l : desc_.lights) {
        l->preprocess(bounds_);
        lights_.push_back(l);
        if (l->type() == Light::Type::Infinite) infinite_.push_back(l.get());
    }
}

void Scene::addShapeData(const ShapeDescription& s) {
    ShapeData sd;
    sd.desc = &s;
    sd.material = s.material ? s.material.get() : defaultMaterial_.get();
    shapes_.push_back(sd);
}

/// Each shape group once as its own Embree scene (its shapes appended to shapes_), each instance as
/// an Embree instance of it (Mitsuba 3 does the same: src/render/shapegroup.cpp, embree_geometry)
/// with the geometry ID shapes + its index, so that a hit's instID finds its InstanceData.
void Scene::addInstances(vec3& lo, vec3& hi) {
    RTCDevice device = static_cast<RTCDevice>(device_);
    struct Group {
        RTCScene scene;
        size_t firstShape;
        vec3 lo, hi;
    };
    std::map<const ShapeGroupDescription*, Group> groups;
    firstInstanceID_ = unsigned(desc_.shapes.size());
    for (size_t k = 0; k < desc_.instances.size(); ++k) {
        const InstanceDescription& inst = desc_.instances[k];
        auto [it, added] = groups.try_emplace(inst.group.get());
        Group& g = it->second;
        if (added) {
            g.scene = rtcNewScene(device);
            rtcSetSceneBuildQuality(g.scene, RTC_BUILD_QUALITY_HIGH);
            groupScenes_.push_back(g.scene);
            g.firstShape = shapes_.size();
            g.lo = vec3(std::numeric_limits<float>::infinity());
            g.hi = vec3(-std::numeric_limits<float>::infinity());
            for (size_t j = 0; j < inst.group->shapes.size(); ++j) {
                addShapeData(inst.group->shapes[j]);
                RTCGeometry geom = shapeGeometry(device, inst.group->shapes[j], g.lo, g.hi, triangles_);
                if (geom) attachGeometry(g.scene, geom, unsigned(j));
                checkDevice(device, "building the geometry of a shape group");
            }
            rtcCommitScene(g.scene);
            checkDevice(device, "building the acceleration structure of a shape group");
        }
        instances_.push_back(InstanceData{InstanceTransform(inst.toWorld), g.firstShape});
        RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_INSTANCE);
        rtcSetGeometryInstancedScene(geom, g.scene);
        rtcSetGeometryTransform(geom, 0, RTC_FORMAT_FLOAT4X4_COLUMN_MAJOR, &inst.toWorld[0][0]);  // glm is column-major
        attachGeometry(static_cast<RTCScene>(scene_), geom, firstInstanceID_ + unsigned(k));
        checkDevice(device, ("placing " + inst.name).c_str());
        if (g.lo.x <= g.hi.x)
            for (int c = 0; c < 8; ++c)
                growBounds(lo, hi, transformPoint(inst.toWorld, vec3(c & 1 ? g.hi.x : g.lo.x, c & 2 ? g.hi.y : g.lo.y, c & 4 ? g.hi.z : g.lo.z)));
    }
}

const ShapeDescription& Scene::shape(int shapeIndex) const { return *shapes_.at(size_t(shapeIndex)).desc; }

Scene::~Scene() {
    if (scene_) rtcReleaseScene(static_cast<RTCScene>(scene_));
    for (void* g : groupScenes_) rtcReleaseScene(static_cast<RTCScene>(g));
    if (device_) rtcReleaseDevice(static_cast<RTCDevice>(device_));
}

namespace {
/// The cylinder's surface interaction at the hit point si.p (Mitsuba 3, src/shapes/cylinder.cpp):
/// with the hit's local coordinates (x, y, z) in the cylinder's frame (world units), u = φ/2π,
/// v = z / length, ∂p/∂u = 2π (−y s + x t), ∂p/∂v = length · axis and the normal
/// normalize(∂p/∂u × ∂p/∂v) (outwards), negated by flip_normals. The hit point is re-projected onto
/// the wall to reduce its error.
void cylinderInteraction(const ShapeDescription& s, SurfaceInteraction& si) {
    const CylinderGeometry& c = s.cylinder;
    const vec3 f = si.p - c.p0;
    const float z = glm::dot(f, c.axis);
    const float x = glm::dot(f, c.s), y = glm::dot(f, c.t);
    const float rl = std::sqrt(x * x + y * y);
    const vec3 radial = rl > 0 ? (x * c.s + y * c.t) / rl : c.s;
    si.p = c.p0 + z * c.axis + s.radius * radial;
    const float phi = std::atan2(y, x);
    si.uv = vec2((phi < 0 ? phi + 2 * kPi : phi) * kInv2Pi, z / c.length);
    const float xr = s.radius * (rl > 0 ? x / rl : 1.0f), yr = s.radius * (rl > 0 ? y / rl : 0.0f);
    si.dpdu = 2 * kPi * (-yr * c.s + xr * c.t);
    si.dpdv = c.length * c.axis;
    si.dpScale = 1.0f;
    vec3 n = glm::normalize(glm::cross(si.dpdu, si.dpdv));
    if (s.flipNormals) n = -n;
    si.ng = si.ns = n;
}

/// The SDF grid's interaction at the hit point si.p in surface voxel `prim` (Mitsuba 3,
/// src/shapes/sdfgrid.cpp): the point moved onto the zero set (one Newton step, sdf_grid.h), the
/// geometric normal from the interpolant's gradient, the shading normal as the shape's `normals`
/// option says; no uv (0, 0), and tangents of a frame around the shading normal.
void sdfInteraction(const ShapeDescription& s, unsigned prim, SurfaceInteraction& si) {
    const SdfGrid& g = *s.sdf;
    si.p = g.projectOntoSurface(prim, si.p);
    si.ng = g.analyticNormal(prim, si.p);
    si.ns = g.shadingNormal(prim, si.p);
    const Frame f = Frame::fromNormal(si.ns);
    si.dpdu = f.s;
    si.dpdv = f.t;
}

/// A triangle's interaction at barycentrics (b1, b2) of triangle `prim`.
void meshInteraction(const ShapeDescription& s, unsigned prim, float b1, float b2, SurfaceInteraction& si) {
    const TriangleMesh& m = *s.mesh;
    const uint32_t* idx = &m.indices[3 * prim];
    const float b0 = 1.0f - b1 - b2;
    si.mesh = &m;  // for mesh_attribute textures
    si.triangle = prim;
    si.bary = vec2(b1, b2);
    const vec3 &p0 = m.positions[idx[0]], &p1 = m.positions[idx[1]], &p2 = m.positions[idx[2]];
    // Barycentric interpolation of the hit point is more accurate than o + t d.
    si.p = b0 * p0 + b1 * p1 + b2 * p2;
    si.ng = glm::normalize(glm::cross(p1 - p0, p2 - p0));
    vec2 uv[3];
    m.cornerUVs(prim, uv);
    const vec2 &uv0 = uv[0], &uv1 = uv[1], &uv2 = uv[2];
    si.uv = b0 * uv0 + b1 * uv1 + b2 * uv2;
    // dp/du and dp/dv from the uv parameterisation (pbrt-v4 §6.5.3, the inverse of the 2×2 uv
    // matrix: p_i − p_2 = (u_i − u_2) ∂p/∂u + (v_i − v_2) ∂p/∂v); for a degenerate uv mapping
    // an edge and the tangent perpendicular to it.
    const vec2 duv02 = uv0 - uv2, duv12 = uv1 - uv2;
    const vec3 dp02 = p0 - p2, dp12 = p1 - p2;
    const float det = duv02.x * duv12.y - duv02.y * duv12.x;
    if (std::abs(det) > 1e-12f) {
        si.dpdu = (duv12.y * dp02 - duv02.y * dp12) / det;
        si.dpdv = (duv02.x * dp12 - duv12.x * dp02) / det;
    } else {
        si.dpdu = p1 - p0;
        si.dpdv = glm::cross(si.ng, si.dpdu);
    }
    if (!m.normals.empty() && !s.faceNormals) {
        vec3 n = b0 * m.normals[idx[0]] + b1 * m.normals[idx[1]] + b2 * m.normals[idx[2]];
        const float len = glm::length(n);
        si.ns = len > 0 ? n / len : si.ng;
    } else {
        si.ns = si.ng;
    }
}

/// The sphere's interaction at the hit point si.p.
void sphereInteraction(const ShapeDescription& s, SurfaceInteraction& si) {
    vec3 n = glm::normalize(si.p - s.center);
    // Re-project onto the sphere to reduce the hit point's error.
    si.p = s.center + s.radius * n;
    if (s.flipNormals) n = -n;
    si.ng = si.ns = n;
    const vec3 world = (si.p - s.center) / s.radius;
    const vec3 local = s.rotated ? glm::transpose(s.frame) * world : world;  // object space
    si.uv = sphereUV(local);
    // Mitsuba 3's sphere parametrisation (src/shapes/sphere.cpp): u = φ/2π, v = θ/π, so
    // ∂p/∂u = 2πr (−y, x, 0) and ∂p/∂v = πr (z cos φ, z sin φ, −sin θ) for the unit local
    // position (x, y, z) = (sin θ cos φ, sin θ sin φ, cos θ). At the poles (sin θ = 0) both
    // degenerate; a tangent pair perpendicular to the axis is used instead.
    // Stored divided by dpScale = 2πr (see SurfaceInteraction).
    si.dpScale = 2 * kPi * s.radius;
    const float rd = std::sqrt(local.x * local.x + local.y * local.y);
    if (rd > 1e-6f) {
        si.dpdu = vec3(-local.y, local.x, 0.0f);
        si.dpdv = 0.5f * vec3(local.z * local.x / rd, local.z * local.y / rd, -rd);
    } else {
        si.dpdu = vec3(1, 0, 0);
        si.dpdv = vec3(0, local.z > 0 ? 0.5f : -0.5f, 0);
    }
    if (s.rotated) {  // back to world space
        si.dpdu = s.frame * si.dpdu;
        si.dpdv = s.frame * si.dpdv;
    }
}
}  // namespace

std::optional<SurfaceInteraction> Scene::intersect(const Ray& ray) const {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRayHit rh;
    rh.ray.org_x = ray.o.x;
    rh.ray.org_y = ray.o.y;
    rh.ray.org_z = ray.o.z;
    rh.ray.dir_x = ray.d.x;
    rh.ray.dir_y = ray.d.y;
    rh.ray.dir_z = ray.d.z;
    rh.ray.tnear = 0.0f;
    rh.ray.tfar = ray.tMax;
    rh.ray.mask = 0xFFFFFFFFu;
    rh.ray.flags = 0;
    rh.ray.time = 0.0f;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    if (embreeGeometries_) rtcIntersect1(static_cast<RTCScene>(scene_), &ctx, &rh);
    for (const FlatShape& f : flat_) {  // as userIntersect does for Embree
        const ShapeDescription& s = *shapes_[f.index].desc;
        const double t = f.cylinder ? CylinderShape::hit(s, 0, rh.ray) : SphereShape::hit(s, 0, rh.ray);
        if (!std::isfinite(t)) continue;
        rh.ray.tfar = float(t);
        rh.hit.u = rh.hit.v = 0.0f;
        rh.hit.primID = 0;
        rh.hit.geomID = f.index;
        rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    }
    // Every return returns `hit`, filled in place, so that the record is never copied (NRVO).
    std::optional<SurfaceInteraction> hit;
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return hit;

    SurfaceInteraction& si = hit.emplace();
    const unsigned inst = rh.hit.instID[0];
    if (inst == RTC_INVALID_GEOMETRY_ID) {
        hitInteraction(rh.hit.geomID, rh.hit.primID, rh.hit.u, rh.hit.v, ray, rh.ray.tfar, si);
        return hit;
    }
    // A hit inside an instance: the shape's interaction in the group's space, then carried to world.
    const InstanceData& in = instances_[inst - firstInstanceID_];
    hitInteraction(in.firstShape + rh.hit.geomID, rh.hit.primID, rh.hit.u, rh.hit.v, in.transform.toObjectRay(ray), rh.ray.tfar, si);
    in.transform.toWorldInteraction(si);
    si.wo = -glm::normalize(ray.d);
    return hit;
}

/// The interaction at a hit of shapes_[index] (primitive prim, barycentrics (b1, b2), distance t
/// along `ray`), in the shape's own space, written into the default-constructed `si`.
void Scene::hitInteraction(size_t index, unsigned prim, float b1, float b2, const Ray& ray, float t, SurfaceInteraction& si) const {
    const ShapeData& sd = shapes_[index];
    const ShapeDescription& s = *sd.desc;
    si.t = t;
    si.p = ray.at(si.t);
    si.wo = -glm::normalize(ray.d);
    si.shapeIndex = int(index);
    si.material = sd.material;
    si.areaLight = sd.areaLight;
    if (s.type == ShapeDescription::Type::Mesh)
        meshInteraction(s, prim, b1, b2, si);
    else if (s.type == ShapeDescription::Type::Cylinder)
        cylinderInteraction(s, si);
    else if (s.type == ShapeDescription::Type::SdfGrid)
        sdfInteraction(s, prim, si);
    else
        sphereInteraction(s, si);
}

bool Scene::occluded(const Ray& ray) const {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRay r;
    r.org_x = ray.o.x;
    r.org_y = ray.o.y;
    r.org_z = ray.o.z;
    r.dir_x = ray.d.x;
    r.dir_y = ray.d.y;
    r.dir_z = ray.d.z;
    r.tnear = 0.0f;
    r.tfar = ray.tMax;
    r.mask = 0xFFFFFFFFu;
    r.flags = 0;
    r.time = 0.0f;
    for (const FlatShape& f : flat_) {  // as userOccluded does for Embree
        const ShapeDescription& s = *shapes_[f.index].desc;
        if (std::isfinite(f.cylinder ? CylinderShape::hit(s, 0, r) : SphereShape::hit(s, 0, r))) return true;
    }
    if (!embreeGeometries_) return false;
    rtcOccluded1(static_cast<RTCScene>(scene_), &ctx, &r);
    return r.tfar < 0;  // Embree sets tfar = -inf on a hit
}

bool Scene::visible(const SurfaceInteraction& from, const vec3& pLight, const vec3& nLight) const {
    const vec3 d = pLight - from.p;
    const vec3 o = offsetRayOrigin(from.p, from.ng, d);
    const vec3 target = glm::dot(nLight, nLight) > 0 ? offsetRayOrigin(pLight, nLight, -d) : pLight;
    const vec3 dd = target - o;
    return !occluded(Ray(o, dd, 1.0f - 1e-4f));
}

bool Scene::visibleInfinite(const SurfaceInteraction& from, const vec3& dir) const {
    return !occluded(from.spawnRay(dir));
}

}  // namespace iris
