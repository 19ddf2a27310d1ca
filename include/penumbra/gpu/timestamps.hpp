#pragma once
// GPU timings from timestamp queries. A GpuTimer holds one query pool for a frame's
// named scopes; the renderer (or any recorder) wraps a pass in a scope, and after the
// frame's fence has signalled read() turns the timestamps into milliseconds.
//
//   timer.begin_frame(cmd);                       // resets the pool, outside rendering
//   { gpu::TimedScope scope(&timer, cmd, "lighting"); lighting.record(cmd, ...); }
//   ... submit and wait ...
//   std::optional<std::vector<gpu::ScopeTime>> times = timer.read();
//
// Scopes must begin and end outside dynamic-rendering instances: inside a multiview
// instance a timestamp would take one query per view.
#include <vulkan/vulkan.h>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "penumbra/gpu/debug_names.hpp"
#include "penumbra/gpu/device.hpp"
#include "penumbra/gpu/handle.hpp"

namespace penumbra::gpu {

struct ScopeTime {
    std::string name;
    double milliseconds = 0.0;
};

class GpuTimer {
public:
    // max_scopes: the most scopes one frame may hold (two queries each).
    GpuTimer(const Device& device, uint32_t max_scopes);

    // False when the graphics queue has no timestamp support (timestampValidBits == 0);
    // every recording call is then a no-op and read() returns nullopt.
    bool supported() const { return valid_bits_ != 0; }
    uint32_t valid_bits() const { return valid_bits_; }
    float period_ns() const { return period_ns_; }  // nanoseconds per timestamp tick

    // Resets the queries and forgets the previous frame's scopes.
    void begin_frame(VkCommandBuffer cmd);
    // Appended to the name of every scope opened from now on (which of several views a pass
    // belongs to); empty by default.
    void set_scope_suffix(std::string suffix) { suffix_ = std::move(suffix); }
    const std::string& scope_suffix() const { return suffix_; }
    // Opens a scope; returns its index for end(). Throws UsageError past max_scopes.
    uint32_t begin(VkCommandBuffer cmd, std::string name);
    void end(VkCommandBuffer cmd, uint32_t scope);

    // The scopes of the last frame in the order they were opened, once its submission has
    // completed. nullopt when timestamps are unsupported or a result is not available yet
    // (VK_NOT_READY: the caller may retry, or drop this frame's timings).
    std::optional<std::vector<ScopeTime>> read() const;

    const Device& device() const { return device_; }

private:
    const Device& device_;
    uint32_t max_scopes_;
    uint32_t valid_bits_ = 0;
    float period_ns_ = 1.0f;
    UniqueQueryPool pool_;
    std::vector<std::string> names_;
    std::vector<bool> ended_;
    std::string suffix_;
};

// A pass: opens a timing scope on construction and closes it on destruction, inside a
// command label of the same name (CommandLabel). The scope is skipped when the timer is
// null, so that recording code can be timed or not with the same calls; the label stays.
class TimedScope {
public:
    TimedScope(const Device& device, GpuTimer* timer, VkCommandBuffer cmd, const std::string& name);
    // With a timer: its device labels the pass.
    TimedScope(GpuTimer& timer, VkCommandBuffer cmd, const std::string& name)
        : TimedScope(timer.device(), &timer, cmd, name) {}
    ~TimedScope();
    TimedScope(const TimedScope&) = delete;
    TimedScope& operator=(const TimedScope&) = delete;

private:
    CommandLabel label_;
    GpuTimer* timer_;
    VkCommandBuffer cmd_;
    uint32_t scope_ = 0;
};

}  // namespace penumbra::gpu
