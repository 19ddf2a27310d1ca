// Embree 3 BVHs for shadow rays. Each mesh becomes one BVH in its model space, and each
// instance an Embree instance of it with the instance's world matrix (two-level BVH), so
// a scene of many copies of a model costs the model once. The scenes are built with
// RTC_SCENE_FLAG_ROBUST: watertight traversal, so a ray through an edge shared by two
// triangles cannot slip between them and report a false light leak.
#include "quality/shadow_ray_tracer.hpp"

#include <glm/gtc/type_ptr.hpp>

#include <embree3/rtcore.h>

#include <algorithm>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "quality/alpha_mask.hpp"

namespace penumbra::quality {
namespace {

// What the occlusion filter needs to alpha-test a hit on one mesh.
struct MaskedMesh {
    const Mesh* mesh = nullptr;
    const Material* material = nullptr;
    const Texture* texture = nullptr;  // may be null (base colour alpha only)
    float cutoff = 0.5f;
};

// Rejects hits where the material's alpha is below its cutoff, so the ray continues
// through the holes of leaves and fences (Embree's filter-function mechanism).
void alpha_test_filter(const RTCFilterFunctionNArguments* args) {
    const auto* masked = static_cast<const MaskedMesh*>(args->geometryUserPtr);
    for (unsigned int i = 0; i < args->N; ++i) {
        if (args->valid[i] != -1) continue;
        const unsigned int triangle = RTCHitN_primID(args->hit, args->N, i);
        const float u = RTCHitN_u(args->hit, args->N, i);
        const float v = RTCHitN_v(args->hit, args->N, i);
        const uint32_t* corner = &masked->mesh->indices[size_t{triangle} * 3];
        const glm::vec2 uv = masked->mesh->vertices[corner[0]].uv * (1.0f - u - v) +
                             masked->mesh->vertices[corner[1]].uv * u + masked->mesh->vertices[corner[2]].uv * v;
        if (material_alpha(*masked->material, masked->texture, uv) < masked->cutoff) args->valid[i] = 0;
    }
}

void throw_on_device_error(RTCDevice device, const char* step) {
    const RTCError error = rtcGetDeviceError(device);
    if (error != RTC_ERROR_NONE) {
        throw std::runtime_error(std::string("Embree: ") + step + " failed (error " +
                                 std::to_string(static_cast<int>(error)) + ")");
    }
}

}  // namespace

struct ShadowRayTracer::Embree {
    RTCDevice device = nullptr;
    RTCScene top = nullptr;
    std::vector<RTCScene> mesh_scenes;   // one per Scene mesh (null for empty meshes)
    std::vector<MaskedMesh> masked;      // filter data per mesh; addresses stay fixed
    std::vector<size_t> scene_instance;  // Scene::instances index of each top-level geometry

    ~Embree() {
        if (top) rtcReleaseScene(top);
        for (RTCScene scene : mesh_scenes) {
            if (scene) rtcReleaseScene(scene);
        }
        if (device) rtcReleaseDevice(device);
    }

    RTCScene new_scene() const {
        RTCScene scene = rtcNewScene(device);
        rtcSetSceneFlags(scene, RTC_SCENE_FLAG_ROBUST);
        rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_HIGH);
        return scene;
    }

    RTCScene build_mesh_scene(const Mesh& mesh, MaskedMesh* mask) const {
        RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
        auto* positions = static_cast<float*>(rtcSetNewGeometryBuffer(
            geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), mesh.vertices.size()));
        for (size_t i = 0; i < mesh.vertices.size(); ++i) {
            for (int axis = 0; axis < 3; ++axis) positions[i * 3 + axis] = mesh.vertices[i].position[axis];
        }
        const size_t triangles = mesh.indices.size() / 3;
        auto* indices = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(
            geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(uint32_t), triangles));
        std::copy(mesh.indices.begin(), mesh.indices.begin() + static_cast<std::ptrdiff_t>(triangles * 3), indices);
        if (mask) {
            rtcSetGeometryUserData(geometry, mask);
            rtcSetGeometryOccludedFilterFunction(geometry, alpha_test_filter);
            rtcSetGeometryIntersectFilterFunction(geometry, alpha_test_filter);
        }
        rtcCommitGeometry(geometry);
        RTCScene scene = new_scene();
        rtcAttachGeometry(scene, geometry);
        rtcReleaseGeometry(geometry);
        rtcCommitScene(scene);
        return scene;
    }

    void add_instance(RTCScene mesh_scene, const glm::mat4& world) const {
        RTCGeometry instance = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_INSTANCE);
        rtcSetGeometryInstancedScene(instance, mesh_scene);
        rtcSetGeometryTimeStepCount(instance, 1);
        rtcSetGeometryTransform(instance, 0, RTC_FORMAT_FLOAT4X4_COLUMN_MAJOR, glm::value_ptr(world));
        rtcCommitGeometry(instance);
        rtcAttachGeometry(top, instance);
        rtcReleaseGeometry(instance);
    }
};

namespace {

// The filter data of a mesh whose material can let light through, or null when opaque.
MaskedMesh* mask_for(const Scene& scene, const Mesh& mesh, MaskedMesh& slot) {
    if (mesh.material >= scene.materials.size()) return nullptr;
    const Material& material = scene.materials[mesh.material];
    const std::optional<float> cutoff = alpha_cutoff(material);
    if (!cutoff) return nullptr;
    const int32_t texture = material.base_color_texture;
    const bool has_texture = texture >= 0 && texture < static_cast<int32_t>(scene.textures.size());
    slot = {&mesh, &material, has_texture ? &scene.textures[texture] : nullptr, *cutoff};
    return &slot;
}

}  // namespace

namespace {

bool traced(const Scene& scene, size_t index, TracedInstances selection, std::span<const size_t> only) {
    if (selection == TracedInstances::Casters && !scene.instances[index].cast_shadows) return false;
    return only.empty() || std::find(only.begin(), only.end(), index) != only.end();
}

RTCRay make_ray(const glm::vec3& origin, const glm::vec3& direction, float min_distance, float max_distance) {
    RTCRay ray{};
    ray.org_x = origin.x;
    ray.org_y = origin.y;
    ray.org_z = origin.z;
    ray.dir_x = direction.x;
    ray.dir_y = direction.y;
    ray.dir_z = direction.z;
    ray.tnear = min_distance;
    ray.tfar = max_distance;
    ray.mask = 0xFFFFFFFFu;
    return ray;
}

}  // namespace

ShadowRayTracer::ShadowRayTracer(const Scene& scene, TracedInstances selection, std::span<const size_t> only)
    : embree_(std::make_unique<Embree>()) {
    embree_->device = rtcNewDevice(nullptr);
    if (!embree_->device) throw std::runtime_error("Embree: cannot create a device");
    embree_->masked.resize(scene.meshes.size());
    embree_->mesh_scenes.resize(scene.meshes.size(), nullptr);
    for (size_t m = 0; m < scene.meshes.size(); ++m) {
        const Mesh& mesh = scene.meshes[m];
        if (mesh.indices.size() < 3 || mesh.vertices.empty()) continue;
        embree_->mesh_scenes[m] = embree_->build_mesh_scene(mesh, mask_for(scene, mesh, embree_->masked[m]));
    }
    throw_on_device_error(embree_->device, "building the mesh BVHs");
    embree_->top = embree_->new_scene();
    for (size_t i = 0; i < scene.instances.size(); ++i) {
        const Instance& instance = scene.instances[i];
        if (instance.mesh >= embree_->mesh_scenes.size() || !embree_->mesh_scenes[instance.mesh]) continue;
        if (!traced(scene, i, selection, only)) continue;  // casters only: as the shadow maps leave it out
        embree_->add_instance(embree_->mesh_scenes[instance.mesh], instance.world);
        embree_->scene_instance.push_back(i);
        triangles_ += scene.meshes[instance.mesh].indices.size() / 3;
    }
    rtcCommitScene(embree_->top);
    throw_on_device_error(embree_->device, "building the instance BVH");
}

ShadowRayTracer::~ShadowRayTracer() = default;

bool ShadowRayTracer::occluded(const glm::vec3& origin, const glm::vec3& direction) const {
    return occluded(origin, direction, std::numeric_limits<float>::infinity());
}

bool ShadowRayTracer::occluded(const glm::vec3& origin, const glm::vec3& direction, float max_distance) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRay ray = make_ray(origin, direction, 0.0f, max_distance);
    rtcOccluded1(embree_->top, &context, &ray);
    return ray.tfar < 0.0f;  // Embree sets tfar to -inf when the ray is occluded
}

std::optional<SurfaceHit> ShadowRayTracer::first_hit(const glm::vec3& origin, const glm::vec3& direction,
                                                     float min_distance, float max_distance) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit query{};
    query.ray = make_ray(origin, direction, min_distance, max_distance);
    query.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    query.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(embree_->top, &context, &query);
    if (query.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;
    // Every top-level geometry is an instance, attached in order: its ID indexes scene_instance.
    return SurfaceHit{query.ray.tfar, embree_->scene_instance.at(query.hit.instID[0])};
}

}  // namespace penumbra::quality
