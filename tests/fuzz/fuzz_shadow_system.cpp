// libFuzzer harness: the public API's input validation and CPU work. Each input is read as
// a short program of calls (add_mesh from arrays, add_instance, set_lights, update_settings,
// prepare with one or several views) with values taken from the input bytes, NaNs and infinities included, on one
// ShadowSystem over lavapipe. Every call must succeed or throw a penumbra::Error; the
// system must stay usable (each input ends by removing what it added).
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <memory>
#include <vector>

#include "penumbra/penumbra.hpp"

namespace {

class Input {
public:
    Input(const uint8_t* data, size_t size) : data_(data), size_(size) {}
    bool empty() const { return offset_ >= size_; }
    uint8_t byte() { return offset_ < size_ ? data_[offset_++] : 0; }
    float number() {
        float value = 0.0f;
        if (offset_ + sizeof(value) <= size_) std::memcpy(&value, data_ + offset_, sizeof(value));
        offset_ += sizeof(value);
        return value;
    }
    penumbra::Vec3 vec3() { return {number(), number(), number()}; }
    uint32_t small(uint32_t bound) { return bound ? byte() % bound : 0; }

private:
    const uint8_t* data_;
    size_t size_;
    size_t offset_ = 0;
};

penumbra::ShadowSystem& shadows() {
    static penumbra::VulkanContext context;
    static penumbra::ShadowSystem system([] {
        penumbra::ShadowSystemDesc desc;
        desc.device = context.device_desc();
        desc.settings.shadow.cascades.resolution = 512;
        desc.settings.local_shadows.resolution = 64;
        // Two sets of maps, each drawing the static changes in its turn: the fuzzed scene
        // edits exercise the change log that both sets read.
        desc.maps_per_frame_in_flight = true;
        return desc;
    }());
    return system;
}

penumbra::MeshData mesh_data(Input& in, std::vector<penumbra::Vec3>& positions, std::vector<uint32_t>& indices) {
    positions.resize(in.small(16));
    for (penumbra::Vec3& p : positions) p = in.vec3();
    indices.resize(in.small(24));
    for (uint32_t& i : indices) i = in.small(20);
    return {positions, indices};
}

penumbra::LightDesc light(Input& in) {
    penumbra::LightDesc desc;
    desc.type = static_cast<penumbra::LightType>(in.small(3));
    desc.direction = in.vec3();
    desc.position = in.vec3();
    desc.outer_angle_degrees = in.number();
    desc.inner_angle_degrees = in.number();
    desc.range = in.number();
    desc.radius = in.number();
    // 0 (the settings' size) to 2048 texels. Larger maps are valid (up to 8192), but lavapipe
    // allocates device memory from the process's own: three 8192-texel cube maps (4.8 GB) are
    // a legitimate request that only the fuzzer's 2 GiB limit refuses, and clearing them on
    // the CPU takes seconds (the first long run's "out-of-memory" and "slow unit").
    desc.shadow_resolution = in.small(33) * 64;
    desc.cast_shadows = in.byte() & 1;
    return desc;
}

penumbra::Mat4 matrix(Input& in) {
    penumbra::Mat4 m;
    for (float& value : m.m) value = in.byte() & 1 ? in.number() : value;
    return m;
}

penumbra::ViewDesc view_desc(Input& in) {
    const penumbra::Vec3 eye = in.vec3();
    penumbra::ViewDesc view = penumbra::look_at_view(eye, in.vec3(), in.vec3(), in.number(), in.number(), in.number(),
                                                     1 + in.small(255), 1 + in.small(255));
    // Half the time the caller's projection: any matrix, from the field of view's on.
    if (in.byte() & 1) {
        penumbra::Mat4 projection = penumbra::reverse_z_projection(view);
        for (float& value : projection.m) value = in.byte() & 1 ? in.number() : value;
        view.projection = projection;
    }
    return view;
}

void run(Input& in, penumbra::ShadowSystem& system, std::vector<penumbra::MeshId>& meshes,
         std::vector<penumbra::InstanceId>& instances) {
    std::vector<penumbra::Vec3> positions;
    std::vector<uint32_t> indices;
    switch (in.small(5)) {
        case 0:
            meshes.push_back(system.add_mesh(mesh_data(in, positions, indices)));
            break;
        case 1:
            if (!meshes.empty()) {
                instances.push_back(system.add_instance(
                    {meshes[in.small(static_cast<uint32_t>(meshes.size()))], matrix(in), in.byte()}));
            }
            break;
        case 2: {
            std::vector<penumbra::LightDesc> lights(in.small(4));
            for (penumbra::LightDesc& desc : lights) desc = light(in);
            system.set_lights(lights);
            break;
        }
        case 3: {
            penumbra::Settings settings = system.settings();
            settings.shadow.cascades.max_distance = in.number();
            settings.shadow.cascades.split_lambda = in.number();
            settings.shadow.bias.normal_offset = in.number();
            system.update_settings(settings);
            break;
        }
        default: {
            // Mostly one view, sometimes several, and now and then none or more than kMaxViews.
            constexpr uint32_t kViewCounts[] = {1, 1, 2, 3, 0, penumbra::kMaxViews + 1};
            std::vector<penumbra::ViewDesc> views(kViewCounts[in.small(6)]);
            for (penumbra::ViewDesc& view : views) view = view_desc(in);
            system.prepare(views);
            break;
        }
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    penumbra::ShadowSystem& system = shadows();
    Input in(data, size);
    std::vector<penumbra::MeshId> meshes;
    std::vector<penumbra::InstanceId> instances;
    while (!in.empty()) {
        try {
            run(in, system, meshes, instances);
        } catch (const penumbra::Error&) {
        }
    }
    for (const penumbra::InstanceId id : instances) system.remove_instance(id);
    for (const penumbra::MeshId id : meshes) system.remove_mesh(id);
    system.set_lights({});
    return 0;
}
