#include "penumbra/gpu/timestamps.hpp"
#include "penumbra/gpu/debug_names.hpp"

#include <string>

#include "penumbra/errors.hpp"
#include "penumbra/gpu/check.hpp"

namespace penumbra::gpu {
namespace {

uint32_t queue_timestamp_bits(const Device& device) {
    return queue_families(device.vk(), device.physical_device()).at(device.queue_family()).timestampValidBits;
}

// Ticks between two timestamps. Only the low valid_bits of a timestamp are meaningful,
// so the difference is taken modulo 2^valid_bits (a counter may wrap between them).
uint64_t elapsed_ticks(uint64_t begin, uint64_t end, uint32_t valid_bits) {
    const uint64_t mask = valid_bits >= 64 ? ~uint64_t{0} : (uint64_t{1} << valid_bits) - 1;
    return (end - begin) & mask;
}

}  // namespace

GpuTimer::GpuTimer(const Device& device, uint32_t max_scopes)
    : device_(device),
      max_scopes_(max_scopes),
      valid_bits_(queue_timestamp_bits(device)),
      period_ns_(device.properties().limits.timestampPeriod) {
    if (!supported()) return;
    VkQueryPoolCreateInfo info{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
    info.queryType = VK_QUERY_TYPE_TIMESTAMP;
    info.queryCount = 2 * max_scopes;
    VkQueryPool pool = VK_NULL_HANDLE;
    PENUMBRA_VK_CHECK(device_->vkCreateQueryPool(device_, &info, nullptr, &pool));
    name_object(device_, VK_OBJECT_TYPE_QUERY_POOL, pool, "timestamp queries");
    pool_ = UniqueQueryPool(device_, pool);
}

void GpuTimer::begin_frame(VkCommandBuffer cmd) {
    names_.clear();
    ended_.clear();
    if (supported()) device_->vkCmdResetQueryPool(cmd, pool_, 0, 2 * max_scopes_);
}

uint32_t GpuTimer::begin(VkCommandBuffer cmd, std::string name) {
    if (names_.size() >= max_scopes_) {
        throw UsageError("GpuTimer: more than " + std::to_string(max_scopes_) + " scopes in one frame");
    }
    const auto scope = static_cast<uint32_t>(names_.size());
    names_.push_back(std::move(name) + suffix_);
    ended_.push_back(false);
    // BOTTOM_OF_PIPE at both ends (for a timestamp the same as ALL_COMMANDS, which the
    // best-practices layer flags): a timestamp is written once every earlier command has
    // finished, so consecutive scopes measure disjoint intervals that add up to at most
    // the frame (TOP_OF_PIPE begins would let a scope start before the previous one ends).
    if (supported()) device_->vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_BOTTOM_OF_PIPE_BIT, pool_, 2 * scope);
    return scope;
}

void GpuTimer::end(VkCommandBuffer cmd, uint32_t scope) {
    ended_.at(scope) = true;
    if (supported()) device_->vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_BOTTOM_OF_PIPE_BIT, pool_, 2 * scope + 1);
}

std::optional<std::vector<ScopeTime>> GpuTimer::read() const {
    if (!supported()) return std::nullopt;
    if (names_.empty()) return std::vector<ScopeTime>{};  // nothing was timed (a cached frame with no pass)
    for (const bool ended : ended_) {
        if (!ended) throw UsageError("GpuTimer: a scope was opened but never closed");
    }
    std::vector<uint64_t> ticks(2 * names_.size());
    // No WAIT flag: a result that is not there yet must not block forever.
    const VkResult result = device_->vkGetQueryPoolResults(device_, pool_, 0, static_cast<uint32_t>(ticks.size()),
                                                           ticks.size() * sizeof(uint64_t), ticks.data(),
                                                           sizeof(uint64_t), VK_QUERY_RESULT_64_BIT);
    if (result == VK_NOT_READY) return std::nullopt;
    PENUMBRA_VK_CHECK(result);
    std::vector<ScopeTime> times;
    for (size_t scope = 0; scope < names_.size(); ++scope) {
        const uint64_t delta = elapsed_ticks(ticks[2 * scope], ticks[2 * scope + 1], valid_bits_);
        times.push_back({names_[scope], static_cast<double>(delta) * period_ns_ * 1e-6});
    }
    return times;
}

TimedScope::TimedScope(const Device& device, GpuTimer* timer, VkCommandBuffer cmd, const std::string& name)
    : label_(device, cmd, timer ? name + timer->scope_suffix() : name), timer_(timer), cmd_(cmd) {
    if (timer_) scope_ = timer_->begin(cmd_, name);
}

TimedScope::~TimedScope() {
    if (timer_) timer_->end(cmd_, scope_);
}

}  // namespace penumbra::gpu
