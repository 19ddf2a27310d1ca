// Where a ShadowSystem's images and buffers get their memory: an engine's allocator
// (DeviceDesc::allocator) serves every one of them and gets every one back, and Penumbra's
// own allocator places many resources in each block of device memory.
#include <map>
#include <stdexcept>
#include <string>

#include "library_fixture.hpp"

namespace penumbra::library_tests {
namespace {

// An engine's allocator as simple as one can be: one vkAllocateMemory per request (mapped
// for host access), with a ledger of what is outstanding.
class LedgerAllocator : public DeviceMemoryAllocator {
public:
    explicit LedgerAllocator(const DeviceDesc& desc) : device_(desc.device) {
        vkGetPhysicalDeviceMemoryProperties(desc.physical_device, &properties_);
    }

    MemoryAllocation allocate(const MemoryRequest& request) override {
        ++requests;
        if (request.host_access) ++host_requests;
        VkMemoryAllocateInfo info{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
        info.allocationSize = request.requirements.size;
        info.memoryTypeIndex = memory_type(request.requirements.memoryTypeBits, request.required_properties);
        MemoryAllocation allocation;
        TEST_VK(vkAllocateMemory(device_, &info, nullptr, &allocation.memory));
        if (request.host_access)
            TEST_VK(vkMapMemory(device_, allocation.memory, 0, VK_WHOLE_SIZE, 0, &allocation.mapped));
        outstanding[allocation.memory] = request.purpose;
        return allocation;
    }

    void free(const MemoryAllocation& allocation) noexcept override {
        if (outstanding.erase(allocation.memory) != 1) ++unknown_frees;
        vkFreeMemory(device_, allocation.memory, nullptr);
    }

    int requests = 0;
    int host_requests = 0;
    int unknown_frees = 0;
    std::map<VkDeviceMemory, std::string> outstanding;  // memory -> purpose

private:
    uint32_t memory_type(uint32_t bits, VkMemoryPropertyFlags wanted) const {
        for (uint32_t i = 0; i < properties_.memoryTypeCount; ++i) {
            if ((bits & (1u << i)) && (properties_.memoryTypes[i].propertyFlags & wanted) == wanted) return i;
        }
        throw std::runtime_error("no memory type");
    }

    VkDevice device_;
    VkPhysicalDeviceMemoryProperties properties_{};
};

using DeviceMemory = LibraryTest;

TEST_F(DeviceMemory, TheCallersAllocatorServesEveryImageAndBufferAndGetsEachBack) {
    LedgerAllocator allocator(device_);
    {
        ShadowSystemDesc desc = system_desc();
        desc.device.allocator = &allocator;
        ShadowSystem shadows(desc);
        const MeshArrays box = box_mesh();
        const MeshArrays ground = ground_mesh();
        add_scene(shadows, box, ground);
        expect_box_shadow_of_the_sun(render_visibility(shadows));
        EXPECT_GT(allocator.host_requests, 0) << "uniforms and uploads are host-visible";
        EXPECT_GT(allocator.requests, allocator.host_requests) << "maps and GPU buffers are device-local";
        EXPECT_EQ(shadows.memory().memory_blocks, 0u) << "Penumbra holds no memory of its own";

        // A resized map is allocated again and the old one given back once no frame uses it
        // (so are the uploads' staging buffers, after the frames in flight).
        for (int frame = 0; frame < 3; ++frame) render_visibility(shadows);
        const auto purposes = [&] {
            std::string list;
            for (const auto& [memory, purpose] : allocator.outstanding) list += purpose + "; ";
            return list;
        };
        const size_t before = allocator.outstanding.size();
        const std::string before_purposes = purposes();
        Settings settings = shadows.settings();
        settings.shadow.cascades.resolution /= 2;
        shadows.update_settings(settings);
        for (int frame = 0; frame < 4; ++frame) render_visibility(shadows);
        EXPECT_EQ(allocator.outstanding.size(), before)
            << "the replaced maps' memory came back: before " << before_purposes << " after " << purposes();
    }
    EXPECT_EQ(allocator.unknown_frees, 0);
    for (const auto& [memory, purpose] : allocator.outstanding) ADD_FAILURE() << "not given back: " << purpose;
}

TEST_F(DeviceMemory, PenumbrasOwnAllocatorPlacesManyResourcesInEachBlock) {
    LedgerAllocator ledger(device_);
    ShadowSystemDesc counted = system_desc();
    counted.device.allocator = &ledger;
    const MeshArrays box = box_mesh();
    const MeshArrays ground = ground_mesh();
    LightDesc spot{LightType::Spot, {0.0f, -1.0f, 0.0f}, {1.0f, 8.0f, 0.0f}};
    const auto build = [&](ShadowSystem& shadows) {
        add_scene(shadows, box, ground);
        const LightDesc lights[] = {{LightType::Directional, {kSunDirection.x, kSunDirection.y, kSunDirection.z}},
                                    spot};
        shadows.set_lights(lights);
        return render_visibility(shadows);
    };
    ShadowSystem with_ledger(counted);
    const VisibilityImage2D expected = build(with_ledger);

    ShadowSystem own(system_desc());
    const VisibilityImage2D image = build(own);
    EXPECT_EQ(image.values, expected.values) << "where the memory comes from changes nothing";
    const uint32_t blocks = own.memory().memory_blocks;
    RecordProperty("memory_blocks", static_cast<int>(blocks));
    RecordProperty("images_and_buffers", static_cast<int>(ledger.outstanding.size()));
    EXPECT_GE(blocks, 1u);
    EXPECT_LE(blocks * 4, ledger.outstanding.size())
        << blocks << " blocks for " << ledger.outstanding.size() << " images and buffers";
}

// An allocator that breaks its contract is named; nothing leaks (the fixture's validation
// layer reports leaked objects at teardown).
class BrokenAllocator : public DeviceMemoryAllocator {
public:
    enum class Fault { NoMemory, Misaligned, Throws };
    BrokenAllocator(const DeviceDesc& desc, Fault fault) : ledger_(desc), fault_(fault) {}
    MemoryAllocation allocate(const MemoryRequest& request) override {
        if (++calls_ < 3) return ledger_.allocate(request);  // a few good ones first
        switch (fault_) {
            case Fault::NoMemory:
                return {};
            case Fault::Misaligned: {
                MemoryRequest larger = request;
                larger.requirements.size += 1;
                MemoryAllocation allocation = ledger_.allocate(larger);
                allocation.offset = 1;
                return allocation;
            }
            case Fault::Throws:
                throw std::runtime_error("the engine's heap is full");
        }
        return {};
    }
    void free(const MemoryAllocation& allocation) noexcept override { ledger_.free(allocation); }
    const LedgerAllocator& ledger() const { return ledger_; }

private:
    LedgerAllocator ledger_;
    Fault fault_;
    int calls_ = 0;
};

TEST_F(DeviceMemory, AnAllocatorThatBreaksItsContractIsNamed) {
    const auto construct = [&](BrokenAllocator& allocator) {
        ShadowSystemDesc desc = system_desc();
        desc.device.allocator = &allocator;
        ShadowSystem shadows(desc);
    };
    {
        BrokenAllocator allocator(device_, BrokenAllocator::Fault::NoMemory);
        try {
            construct(allocator);
            ADD_FAILURE() << "no error";
        } catch (const DeviceError& error) {
            EXPECT_NE(std::string(error.what()).find("DeviceMemoryAllocator::allocate returned no memory ("),
                      std::string::npos)
                << error.what();
        }
        EXPECT_TRUE(allocator.ledger().outstanding.empty());
    }
    {
        BrokenAllocator allocator(device_, BrokenAllocator::Fault::Misaligned);
        try {
            construct(allocator);
            ADD_FAILURE() << "no error";
        } catch (const UsageError& error) {
            EXPECT_NE(std::string(error.what())
                          .find("DeviceMemoryAllocator::allocate returned offset 1, not a "
                                "multiple of the alignment"),
                      std::string::npos)
                << error.what();
        }
        EXPECT_TRUE(allocator.ledger().outstanding.empty());
    }
    {
        BrokenAllocator allocator(device_, BrokenAllocator::Fault::Throws);
        try {
            construct(allocator);
            ADD_FAILURE() << "no error";
        } catch (const std::runtime_error& error) {
            EXPECT_STREQ(error.what(), "the engine's heap is full");
        }
        EXPECT_TRUE(allocator.ledger().outstanding.empty());
    }
}

}  // namespace
}  // namespace penumbra::library_tests
