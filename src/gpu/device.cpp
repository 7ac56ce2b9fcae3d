// Instance, physical-device selection, logical device, submission and validation messages.
#include <algorithm>
#include <cstdio>
#include <cstring>

#include "gpu/vk_internal.h"

namespace penumbra::gpu {

const char* vkResultName(VkResult result) {
    switch (result) {
        case VK_SUCCESS: return "VK_SUCCESS";
        case VK_NOT_READY: return "VK_NOT_READY";
        case VK_TIMEOUT: return "VK_TIMEOUT";
        case VK_INCOMPLETE: return "VK_INCOMPLETE";
        case VK_ERROR_OUT_OF_HOST_MEMORY: return "VK_ERROR_OUT_OF_HOST_MEMORY";
        case VK_ERROR_OUT_OF_DEVICE_MEMORY: return "VK_ERROR_OUT_OF_DEVICE_MEMORY";
        case VK_ERROR_INITIALIZATION_FAILED: return "VK_ERROR_INITIALIZATION_FAILED";
        case VK_ERROR_DEVICE_LOST: return "VK_ERROR_DEVICE_LOST";
        case VK_ERROR_MEMORY_MAP_FAILED: return "VK_ERROR_MEMORY_MAP_FAILED";
        case VK_ERROR_LAYER_NOT_PRESENT: return "VK_ERROR_LAYER_NOT_PRESENT";
        case VK_ERROR_EXTENSION_NOT_PRESENT: return "VK_ERROR_EXTENSION_NOT_PRESENT";
        case VK_ERROR_FEATURE_NOT_PRESENT: return "VK_ERROR_FEATURE_NOT_PRESENT";
        case VK_ERROR_INCOMPATIBLE_DRIVER: return "VK_ERROR_INCOMPATIBLE_DRIVER";
        case VK_ERROR_TOO_MANY_OBJECTS: return "VK_ERROR_TOO_MANY_OBJECTS";
        case VK_ERROR_FORMAT_NOT_SUPPORTED: return "VK_ERROR_FORMAT_NOT_SUPPORTED";
        case VK_ERROR_OUT_OF_POOL_MEMORY: return "VK_ERROR_OUT_OF_POOL_MEMORY";
        default: return "VkResult(other)";
    }
}

namespace {

VKAPI_ATTR VkBool32 VKAPI_CALL onDebugMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                              VkDebugUtilsMessageTypeFlagsEXT,
                                              const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
    auto* impl = static_cast<Device::Impl*>(user);
    if (severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT) {
        const std::string message = data && data->pMessage ? data->pMessage : "(no message)";
        std::fprintf(stderr, "penumbra: Vulkan validation: %s\n", message.c_str());
        std::lock_guard lock(impl->messagesMutex);
        impl->validationMessages.push_back(message);
    }
    return VK_FALSE;
}

bool hasLayer(const char* name) {
    uint32_t count = 0;
    vkEnumerateInstanceLayerProperties(&count, nullptr);
    std::vector<VkLayerProperties> layers(count);
    vkEnumerateInstanceLayerProperties(&count, layers.data());
    return std::any_of(layers.begin(), layers.end(), [&](const auto& l) { return std::strcmp(l.layerName, name) == 0; });
}

bool hasDeviceExtension(VkPhysicalDevice physicalDevice, const char* name) {
    uint32_t count = 0;
    vkEnumerateDeviceExtensionProperties(physicalDevice, nullptr, &count, nullptr);
    std::vector<VkExtensionProperties> extensions(count);
    vkEnumerateDeviceExtensionProperties(physicalDevice, nullptr, &count, extensions.data());
    return std::any_of(extensions.begin(), extensions.end(),
                       [&](const auto& e) { return std::strcmp(e.extensionName, name) == 0; });
}

bool hasInstanceExtension(const char* name) {
    uint32_t count = 0;
    vkEnumerateInstanceExtensionProperties(nullptr, &count, nullptr);
    std::vector<VkExtensionProperties> extensions(count);
    vkEnumerateInstanceExtensionProperties(nullptr, &count, extensions.data());
    return std::any_of(extensions.begin(), extensions.end(),
                       [&](const auto& e) { return std::strcmp(e.extensionName, name) == 0; });
}

// VK_EXT_debug_utils is enabled whenever the loader offers it, so object names reach RenderDoc and
// Nsight captures; the validation layer is only loaded on request.
VkInstance createInstance(bool validation, bool synchronizationValidation) {
    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "penumbra";
    app.pEngineName = "penumbra";
    app.apiVersion = VK_API_VERSION_1_3;
    std::vector<const char*> layers;
    std::vector<const char*> extensions;
    if (validation) {
        if (!hasLayer("VK_LAYER_KHRONOS_validation"))
            throw Error("Vulkan validation requested but VK_LAYER_KHRONOS_validation is not installed "
                        "(Debian package vulkan-validationlayers)");
        layers.push_back("VK_LAYER_KHRONOS_validation");
    }
    if (validation || hasInstanceExtension(VK_EXT_DEBUG_UTILS_EXTENSION_NAME))
        extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    info.pApplicationInfo = &app;
    info.enabledLayerCount = uint32_t(layers.size());
    info.ppEnabledLayerNames = layers.data();
    info.enabledExtensionCount = uint32_t(extensions.size());
    info.ppEnabledExtensionNames = extensions.data();
    const VkValidationFeatureEnableEXT synchronization = VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT;
    VkValidationFeaturesEXT features{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT};
    features.enabledValidationFeatureCount = 1;
    features.pEnabledValidationFeatures = &synchronization;
    if (validation && synchronizationValidation) info.pNext = &features;
    VkInstance instance = VK_NULL_HANDLE;
    const VkResult result = vkCreateInstance(&info, nullptr, &instance);
    if (result != VK_SUCCESS)
        throw Error(std::string("no Vulkan device: vkCreateInstance failed with ") + vkResultName(result) +
                    " (is a Vulkan driver such as mesa-vulkan-drivers installed?)");
    return instance;
}

std::vector<VkPhysicalDevice> enumerateUsable(VkInstance instance) {
    uint32_t count = 0;
    vkEnumeratePhysicalDevices(instance, &count, nullptr);
    std::vector<VkPhysicalDevice> all(count);
    vkEnumeratePhysicalDevices(instance, &count, all.data());
    std::vector<VkPhysicalDevice> usable;
    for (VkPhysicalDevice pd : all) {
        VkPhysicalDeviceProperties props;
        vkGetPhysicalDeviceProperties(pd, &props);
        if (props.apiVersion >= VK_API_VERSION_1_3 && hasDeviceExtension(pd, VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME))
            usable.push_back(pd);
    }
    return usable;
}

DeviceInfo describe(VkPhysicalDevice pd, uint32_t index) {
    VkPhysicalDeviceDriverProperties driver{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
    VkPhysicalDeviceProperties2 props{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
    props.pNext = &driver;
    vkGetPhysicalDeviceProperties2(pd, &props);
    DeviceInfo info;
    info.name = props.properties.deviceName;
    info.driver = std::string(driver.driverName) + " " + driver.driverInfo;
    info.isCpu = props.properties.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU;
    info.index = index;
    return info;
}

// auto: discrete GPU, else integrated GPU, else any GPU, else CPU (lavapipe).
uint32_t choosePhysicalDevice(const std::vector<VkPhysicalDevice>& devices, const std::string& choice) {
    if (devices.empty())
        throw Error("no Vulkan device: no Vulkan 1.3 device with VK_KHR_push_descriptor was found");
    auto typeOf = [&](uint32_t i) {
        VkPhysicalDeviceProperties props;
        vkGetPhysicalDeviceProperties(devices[i], &props);
        return props.deviceType;
    };
    auto firstOf = [&](VkPhysicalDeviceType type) -> int {
        for (uint32_t i = 0; i < devices.size(); ++i)
            if (typeOf(i) == type) return int(i);
        return -1;
    };
    if (choice == "cpu") {
        const int i = firstOf(VK_PHYSICAL_DEVICE_TYPE_CPU);
        if (i < 0) throw Error("no Vulkan device: device kind cpu asks for a CPU device (lavapipe) and none is present");
        return uint32_t(i);
    }
    const int discrete = firstOf(VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU);
    const int integrated = firstOf(VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU);
    const int virtualGpu = firstOf(VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU);
    const int gpu = discrete >= 0 ? discrete : integrated >= 0 ? integrated : virtualGpu;
    if (choice == "gpu") {
        if (gpu < 0) throw Error("no Vulkan device: device kind gpu asks for a GPU and only a CPU device is present");
        return uint32_t(gpu);
    }
    if (choice == "auto") return gpu >= 0 ? uint32_t(gpu) : 0u;
    char* end = nullptr;
    const long index = std::strtol(choice.c_str(), &end, 10);
    if (choice.empty() || *end != '\0' || index < 0)
        throw Error("device kind must be auto, gpu, cpu or a device index, not '" + choice + "'");
    if (size_t(index) >= devices.size())
        throw Error("no Vulkan device: device index " + choice + " is out of range (" + std::to_string(devices.size()) +
                    " usable devices)");
    return uint32_t(index);
}

}  // namespace


namespace {

void installMessenger(Device::Impl& d) {
    VkDebugUtilsMessengerCreateInfoEXT info{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    info.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                       VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
    info.pfnUserCallback = onDebugMessage;
    info.pUserData = &d;
    auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(d.instance, "vkCreateDebugUtilsMessengerEXT"));
    if (create) VK_CHECK(create(d.instance, &info, nullptr, &d.messenger));
}

uint32_t findQueueFamily(VkPhysicalDevice physicalDevice, const std::string& name) {
    uint32_t familyCount = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(physicalDevice, &familyCount, nullptr);
    std::vector<VkQueueFamilyProperties> families(familyCount);
    vkGetPhysicalDeviceQueueFamilyProperties(physicalDevice, &familyCount, families.data());
    for (uint32_t i = 0; i < familyCount; ++i) {
        const auto need = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
        if ((families[i].queueFlags & need) == need) return i;
    }
    throw Error("no Vulkan device: " + name + " has no graphics+compute queue");
}

// The compute shaders' subgroup operations (the compute rasterizers' ballots, the tight fit's depth
// reduction's per-bin min and max): optional in Vulkan 1.3 beyond the basic ones, so checked. `who`
// begins the message ("no Vulkan device", "external Vulkan device").
void requireComputeSubgroups(VkPhysicalDevice physicalDevice, const std::string& who, const std::string& name,
                             const DeviceFaultInjection& faults) {
    VkPhysicalDeviceSubgroupProperties subgroups{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_PROPERTIES};
    VkPhysicalDeviceProperties2 properties{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
    properties.pNext = &subgroups;
    vkGetPhysicalDeviceProperties2(physicalDevice, &properties);
    if (faults.noSubgroupArithmetic) subgroups.supportedOperations &= ~VK_SUBGROUP_FEATURE_ARITHMETIC_BIT;
    constexpr VkSubgroupFeatureFlags kNeeded =
        VK_SUBGROUP_FEATURE_BASIC_BIT | VK_SUBGROUP_FEATURE_BALLOT_BIT | VK_SUBGROUP_FEATURE_ARITHMETIC_BIT;
    if (!(subgroups.supportedStages & VK_SHADER_STAGE_COMPUTE_BIT) || (subgroups.supportedOperations & kNeeded) != kNeeded)
        throw Error(who + ": " + name + " lacks basic, ballot and arithmetic subgroup operations in compute shaders");
}

// R16_UNORM sampled and stored in optimal tiling (what the virtual pools need besides the feature), unless
// the faults say otherwise.
bool r16StorageImages(VkPhysicalDevice physicalDevice, const DeviceFaultInjection& faults) {
    VkFormatProperties r16{};
    vkGetPhysicalDeviceFormatProperties(physicalDevice, VK_FORMAT_R16_UNORM, &r16);
    constexpr VkFormatFeatureFlags kPoolFeatures = VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT | VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT;
    return !faults.noStorageImageExtendedFormats && (r16.optimalTilingFeatures & kPoolFeatures) == kPoolFeatures;
}

VkDevice createLogicalDevice(VkPhysicalDevice physicalDevice, uint32_t queueFamily, const std::string& name,
                             bool memoryBudget, bool& bufferInt64Atomics, bool& storageBufferArrayIndexing,
                             bool& timelineSemaphores, bool& storageImageExtendedFormats, const DeviceFaultInjection& faults) {
    VkPhysicalDeviceFeatures supported{};
    vkGetPhysicalDeviceFeatures(physicalDevice, &supported);
    VkPhysicalDeviceVulkan13Features features13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    features13.dynamicRendering = VK_TRUE;
    features13.synchronization2 = VK_TRUE;
    // Lets a fragment shader leave some of the vertex shader's outputs unread (the depth prepass and
    // the full-screen resolve) without validation warnings; mandatory in Vulkan 1.3.
    features13.maintenance4 = VK_TRUE;
    VkPhysicalDeviceVulkan12Features supported12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
    VkPhysicalDeviceFeatures2 supportedAll{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    supportedAll.pNext = &supported12;
    vkGetPhysicalDeviceFeatures2(physicalDevice, &supportedAll);
    if (!supported12.drawIndirectCount)
        throw Error("no Vulkan device: " + name + " lacks drawIndirectCount (needed for GPU-culled shadow draws)");
    VkPhysicalDeviceVulkan12Features features12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
    features12.pNext = &features13;
    features12.drawIndirectCount = VK_TRUE;
    // The visibility-buffer main view's 64-bit atomicMax (render/visibility_pass.h), where supported.
    bufferInt64Atomics = supported.shaderInt64 && supported12.shaderBufferInt64Atomics;
    features12.shaderBufferInt64Atomics = bufferInt64Atomics;
    // Frames recorded into an embedder's command buffer complete on a timeline value (ShadowSystem).
    timelineSemaphores = supported12.timelineSemaphore;
    features12.timelineSemaphore = timelineSemaphores;
    VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    features.pNext = &features12;
    if (!supported.depthClamp) throw Error("no Vulkan device: " + name + " lacks depthClamp (needed for shadow pancaking)");
    features.features.depthClamp = VK_TRUE;
    features.features.shaderStorageImageWriteWithoutFormat = supported.shaderStorageImageWriteWithoutFormat;
    // Storage images of R16_UNORM (the virtual shadow maps' pools of 16-bit depth codes), where supported.
    storageImageExtendedFormats = supported.shaderStorageImageExtendedFormats && r16StorageImages(physicalDevice, faults);
    features.features.shaderStorageImageExtendedFormats = storageImageExtendedFormats;
    features.features.fragmentStoresAndAtomics = supported.fragmentStoresAndAtomics;
    features.features.shaderInt64 = bufferInt64Atomics;
    // Indirect draws that name their instance (firstInstance) and many draws per call: the GPU-culled
    // shadow draws and the forward main pass's opaque draws.
    features.features.drawIndirectFirstInstance = supported.drawIndirectFirstInstance;
    features.features.multiDrawIndirect = supported.multiDrawIndirect;
    // Arrays of storage buffers indexed per workgroup or dispatch: the culling lists split over buffers
    // (render/gpu_scene.h splitVisibleLists), where supported.
    storageBufferArrayIndexing = supported.shaderStorageBufferArrayDynamicIndexing;
    features.features.shaderStorageBufferArrayDynamicIndexing = storageBufferArrayIndexing;

    const float priority = 1.0f;
    VkDeviceQueueCreateInfo queueInfo{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    queueInfo.queueFamilyIndex = queueFamily;
    queueInfo.queueCount = 1;
    queueInfo.pQueuePriorities = &priority;
    std::vector<const char*> extensions = {VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME};
    if (memoryBudget) extensions.push_back(VK_EXT_MEMORY_BUDGET_EXTENSION_NAME);
    VkDeviceCreateInfo deviceInfo{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
    deviceInfo.pNext = &features;
    deviceInfo.queueCreateInfoCount = 1;
    deviceInfo.pQueueCreateInfos = &queueInfo;
    deviceInfo.enabledExtensionCount = uint32_t(extensions.size());
    deviceInfo.ppEnabledExtensionNames = extensions.data();
    VkDevice device = VK_NULL_HANDLE;
    VK_CHECK(vkCreateDevice(physicalDevice, &deviceInfo, nullptr, &device));
    return device;
}

void nameMemory(void* user, VkDeviceMemory memory, const std::string& name) {
    static_cast<Device::Impl*>(user)->setDebugName(VK_OBJECT_TYPE_DEVICE_MEMORY, uint64_t(memory), name);
}

}  // namespace

std::vector<DeviceInfo> Device::listDevices() {
    VkInstance instance = createInstance(false, false);
    std::vector<DeviceInfo> result;
    const auto devices = enumerateUsable(instance);
    for (uint32_t i = 0; i < devices.size(); ++i) result.push_back(describe(devices[i], i));
    vkDestroyInstance(instance, nullptr);
    return result;
}

Device::Device(const DeviceOptions& options) : impl_(std::make_unique<Impl>()) {
    try {
        createOwnDevice(options);
        initialize();
    } catch (...) {
        release();  // no destructor runs for a half-made object: free what was made, then report
        throw;
    }
}

void Device::createOwnDevice(const DeviceOptions& options) {
    Impl& d = *impl_;
    d.options = options;
    d.instance = createInstance(options.validation, options.synchronizationValidation);
    if (options.validation) installMessenger(d);
    const auto devices = enumerateUsable(d.instance);
    const uint32_t chosen = choosePhysicalDevice(devices, options.device);
    d.physicalDevice = devices[chosen];
    d.info = describe(d.physicalDevice, chosen);
    d.queueFamily = findQueueFamily(d.physicalDevice, d.info.name);
    d.memoryBudget = hasDeviceExtension(d.physicalDevice, VK_EXT_MEMORY_BUDGET_EXTENSION_NAME);
    requireComputeSubgroups(d.physicalDevice, "no Vulkan device", d.info.name, options.faults);
    d.device = createLogicalDevice(d.physicalDevice, d.queueFamily, d.info.name, d.memoryBudget, d.bufferInt64Atomics,
                                   d.storageBufferArrayIndexing, d.timelineSemaphores, d.storageImageExtendedFormats,
                                   options.faults);
    vkGetDeviceQueue(d.device, d.queueFamily, 0, &d.queue);
}

Device::Device(const ExternalVulkanDevice& external, const DeviceOptions& options) : impl_(std::make_unique<Impl>()) {
    Impl& d = *impl_;
    d.options = options;
    d.ownsDevice = false;
    d.instance = reinterpret_cast<VkInstance>(external.instance);
    d.physicalDevice = reinterpret_cast<VkPhysicalDevice>(external.physicalDevice);
    d.device = reinterpret_cast<VkDevice>(external.device);
    d.queue = reinterpret_cast<VkQueue>(external.queue);
    d.queueFamily = external.queueFamily;
    d.bufferInt64Atomics = external.bufferInt64Atomics;
    d.timelineSemaphores = external.timelineSemaphores;
    d.storageImageExtendedFormats = external.storageImageExtendedFormats && r16StorageImages(d.physicalDevice, options.faults);
    if (!d.instance || !d.physicalDevice || !d.device || !d.queue)
        throw Error("external Vulkan device: instance, physical device, device and queue are all required");
    d.info = describe(d.physicalDevice, 0);
    try {
        if (!hasDeviceExtension(d.physicalDevice, VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME))
            throw Error("external Vulkan device: " + d.info.name + " lacks VK_KHR_push_descriptor");
        requireComputeSubgroups(d.physicalDevice, "external Vulkan device", d.info.name, options.faults);
        initialize();
    } catch (...) {
        release();
        throw;
    }
}

void Device::initialize() {
    Impl& d = *impl_;
    if (d.options.framesInFlight < 1 || d.options.framesInFlight > 4)
        throw Error("framesInFlight = " + std::to_string(d.options.framesInFlight) + " is out of range (allowed 1..4)");
    vkGetPhysicalDeviceProperties(d.physicalDevice, &d.properties);
    vkGetPhysicalDeviceMemoryProperties(d.physicalDevice, &d.memoryProperties);
    uint32_t familyCount = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(d.physicalDevice, &familyCount, nullptr);
    std::vector<VkQueueFamilyProperties> families(familyCount);
    vkGetPhysicalDeviceQueueFamilyProperties(d.physicalDevice, &familyCount, families.data());
    d.timestampsSupported = d.options.timestamps && d.queueFamily < familyCount &&
                            families[d.queueFamily].timestampValidBits > 0 &&
                            d.properties.limits.timestampComputeAndGraphics;
    d.cmdPushDescriptorSet = reinterpret_cast<PFN_vkCmdPushDescriptorSetKHR>(
        vkGetDeviceProcAddr(d.device, "vkCmdPushDescriptorSetKHR"));
    d.setObjectName = reinterpret_cast<PFN_vkSetDebugUtilsObjectNameEXT>(
        vkGetInstanceProcAddr(d.instance, "vkSetDebugUtilsObjectNameEXT"));
    d.memory = std::make_unique<MemoryAllocator>(d.device, d.memoryProperties);
    d.memory->setOnNewMemory(nameMemory, &d);
    d.memory->failRequestAt(d.options.faults.failAllocation);
    d.memory->fillNewAllocations(uint8_t(d.options.faults.garbageByte));

    VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    poolInfo.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    poolInfo.queueFamilyIndex = d.queueFamily;
    VK_CHECK(vkCreateCommandPool(d.device, &poolInfo, nullptr, &d.immediatePool));
    VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VK_CHECK(vkCreateFence(d.device, &fenceInfo, nullptr, &d.immediateFence));
    if (d.timestampsSupported) {
        VkQueryPoolCreateInfo queryInfo{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
        queryInfo.queryType = VK_QUERY_TYPE_TIMESTAMP;
        queryInfo.queryCount = d.timestampsPerFrame * (d.options.framesInFlight + 1);  // + immediate lists
        VK_CHECK(vkCreateQueryPool(d.device, &queryInfo, nullptr, &d.timestampPool));
    }
    d.loadPipelineCache();
    d.createFrames(d.options.framesInFlight);
    d.createUploadRings(*this);
    d.startWorker();
}

Device::~Device() { release(); }

void Device::release() {
    Impl& d = *impl_;
    if (d.device) {
        d.stopWorkerThread();
        try {
            waitIdle();
        } catch (const Error&) {
            // Device lost at shutdown: the objects are destroyed regardless.
        }
        d.destroyFrames();
        d.destroyGarbage(d.pendingGarbage);
        d.pipelines.forEachLive([&](uint32_t, PipelineResource& p) { d.destroyNow(p); });
        d.destroyParkedPipelines();
        d.tables.forEachLive([&](uint32_t, TextureTableResource& t) { d.destroyNow(t); });
        d.samplers.forEachLive([&](uint32_t, VkSampler& s) { vkDestroySampler(d.device, s, nullptr); });
        d.textures.forEachLive([&](uint32_t, TextureResource& t) { d.destroyNow(t); });
        d.buffers.forEachLive([&](uint32_t, BufferResource& b) { d.destroyNow(b); });
        if (!d.lost) d.savePipelineCache();
        if (d.pipelineCache) vkDestroyPipelineCache(d.device, d.pipelineCache, nullptr);
        if (d.timestampPool) vkDestroyQueryPool(d.device, d.timestampPool, nullptr);
        if (d.immediateFence) vkDestroyFence(d.device, d.immediateFence, nullptr);
        if (d.immediatePool) vkDestroyCommandPool(d.device, d.immediatePool, nullptr);
        d.memory.reset();
        if (d.ownsDevice) vkDestroyDevice(d.device, nullptr);
        d.device = VK_NULL_HANDLE;
    }
    if (!d.ownsDevice) return;
    if (d.messenger) {
        auto destroyMessenger = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(d.instance, "vkDestroyDebugUtilsMessengerEXT"));
        if (destroyMessenger) destroyMessenger(d.instance, d.messenger, nullptr);
        d.messenger = VK_NULL_HANDLE;
    }
    if (d.instance) vkDestroyInstance(d.instance, nullptr);
    d.instance = VK_NULL_HANDLE;
}

const DeviceInfo& Device::info() const { return impl_->info; }
uint32_t Device::maxImageSize() const {
    const uint32_t real = impl_->properties.limits.maxImageDimension2D;
    const uint32_t injected = impl_->options.faults.maxImageSize;
    return injected > 0 ? std::min(real, injected) : real;
}

uint64_t Device::maxStorageBufferRange() const {
    const uint64_t real = impl_->properties.limits.maxStorageBufferRange;
    const uint64_t injected = impl_->options.faults.maxStorageBufferRange;
    return injected > 0 ? std::min(real, injected) : real;
}
uint32_t Device::maxDrawIndirectCount() const {
    const uint32_t real = impl_->properties.limits.maxDrawIndirectCount;
    const uint32_t injected = impl_->options.faults.maxDrawIndirectCount;
    return injected > 0 ? std::min(real, injected) : real;
}
bool Device::lost() const { return impl_->lost; }
bool Device::hasTimestamps() const { return impl_->timestampsSupported; }
bool Device::hasBufferInt64Atomics() const { return impl_->bufferInt64Atomics; }
bool Device::hasStorageBufferArrayIndexing() const { return impl_->storageBufferArrayIndexing; }
bool Device::hasTimelineSemaphores() const { return impl_->timelineSemaphores; }
bool Device::hasStorageImageExtendedFormats() const { return impl_->storageImageExtendedFormats; }
const DeviceFaultInjection& Device::faults() const { return impl_->options.faults; }

uint64_t Device::spinWaitPolls() const { return impl_->spinWaitPolls; }

uint32_t Device::validationMessageCount() const {
    std::lock_guard lock(impl_->messagesMutex);
    return uint32_t(impl_->validationMessages.size());
}

std::vector<std::string> Device::validationMessages() const {
    std::lock_guard lock(impl_->messagesMutex);
    return impl_->validationMessages;
}

void Device::Impl::setDebugName(VkObjectType type, uint64_t handle, const std::string& name) {
    if (!setObjectName || !handle || name.empty()) return;
    VkDebugUtilsObjectNameInfoEXT info{VK_STRUCTURE_TYPE_DEBUG_UTILS_OBJECT_NAME_INFO_EXT};
    info.objectType = type;
    info.objectHandle = handle;
    info.pObjectName = name.c_str();
    if (setObjectName(device, &info) == VK_SUCCESS) ++debugNamesSet;
}

ObjectCounts Device::objectCounts() const {
    const Impl& d = *impl_;
    ObjectCounts counts;
    counts.buffers = d.buffers.liveCount();
    counts.textures = d.textures.liveCount();
    counts.samplers = d.samplers.liveCount();
    counts.pipelines = d.pipelines.liveCount();
    counts.textureTables = d.tables.liveCount();
    counts.memoryBlocks = d.memory->blockCount();
    counts.memoryBlockBytes = d.memory->blockBytes();
    counts.memoryUsedBytes = d.memory->usedBytes();
    counts.memoryAllocations = d.memory->allocationCalls();
    counts.pendingDestroys = d.pendingGarbage.count();
    for (const FrameContext& frame : d.frames) counts.pendingDestroys += frame.garbage.count();
    counts.objectsCreated = d.objectsCreated;
    counts.lastObjectName = d.lastObjectName;
    counts.submits = d.submits;
    counts.deviceWaits = d.deviceWaits;
    counts.debugNamesSet = d.debugNamesSet;
    counts.pipelinesCompiled = d.pipelinesCompiled;
    counts.pipelinesReused = d.pipelinesReused;
    counts.pipelinesParked = uint32_t(d.parkedPipelines.size());
    return counts;
}

uint64_t Device::deviceMemoryBytes() const {
    const Impl& d = *impl_;
    if (!d.memoryBudget) return d.memory->blockBytes();
    VkPhysicalDeviceMemoryBudgetPropertiesEXT budget{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MEMORY_BUDGET_PROPERTIES_EXT};
    VkPhysicalDeviceMemoryProperties2 properties{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MEMORY_PROPERTIES_2};
    properties.pNext = &budget;
    vkGetPhysicalDeviceMemoryProperties2(d.physicalDevice, &properties);
    uint64_t total = 0;
    for (uint32_t heap = 0; heap < properties.memoryProperties.memoryHeapCount; ++heap)
        if (properties.memoryProperties.memoryHeaps[heap].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT)
            total += budget.heapUsage[heap];
    return total;
}

}  // namespace penumbra::gpu
