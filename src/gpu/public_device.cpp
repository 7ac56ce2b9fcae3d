// penumbra::Device, the public face of gpu::Device.
#include "gpu/device_access.h"
#include "gpu/frame_graph.h"

namespace penumbra {

// Both read PENUMBRA_FAULT_INJECTION (gpu/device_faults.h), so that the CLI's process tests can make
// the device fail.
Device::Device(const DeviceOptions& options)
    : device_(std::make_unique<gpu::Device>(gpu::DeviceOptions(options, gpu::faultInjectionFromEnvironment()))) {}
Device::Device(const ExternalVulkanDevice& external, const DeviceOptions& options)
    : device_(std::make_unique<gpu::Device>(external, gpu::DeviceOptions(options, gpu::faultInjectionFromEnvironment()))) {}
Device::Device(std::unique_ptr<gpu::Device> device) : device_(std::move(device)) {}
Device::~Device() = default;
Device::Device(Device&&) noexcept = default;
Device& Device::operator=(Device&&) noexcept = default;

const DeviceInfo& Device::info() const { return device_->info(); }
std::vector<DeviceInfo> Device::list() { return gpu::Device::listDevices(); }
uint32_t Device::validationMessageCount() const { return device_->validationMessageCount(); }
std::vector<std::string> Device::validationMessages() const { return device_->validationMessages(); }
uint64_t Device::deviceMemoryBytes() const { return device_->deviceMemoryBytes(); }
void Device::waitIdle() { device_->waitIdle(); }
uint32_t Device::maxImageSize() const { return device_->maxImageSize(); }
bool Device::lost() const { return device_->lost(); }

DeviceObjectCounts Device::liveObjects() const { return device_->objectCounts(); }
void Device::recordFrameGraph(bool on) { device_->frameGraph().recordPasses = on; }
std::string Device::frameGraphText(const std::string& format) const {
    return gpu::printFrameGraph(device_->frameGraph(), format);
}

Device DeviceAccess::makeDevice(const gpu::DeviceOptions& options) {
    return Device(std::make_unique<gpu::Device>(options));
}

}  // namespace penumbra
