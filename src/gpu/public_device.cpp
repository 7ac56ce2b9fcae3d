// penumbra::Device, the public face of gpu::Device.
#include "gpu/device.h"

namespace penumbra {

Device::Device(const DeviceOptions& options) : device_(std::make_unique<gpu::Device>(options)) {}
Device::Device(const ExternalVulkanDevice& external, const DeviceOptions& options)
    : device_(std::make_unique<gpu::Device>(external, options)) {}
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

}  // namespace penumbra
