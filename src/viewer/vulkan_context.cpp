#include "viewer/vulkan_context.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <vector>

#include <GLFW/glfw3.h>

#include "penumbra/error.h"
#include "penumbra/vulkan.h"

namespace penumbra::viewer {

void checkVk(VkResult result, const char* call) {
    if (result != VK_SUCCESS) throw Error(std::string(call) + " failed (VkResult " + std::to_string(int(result)) + ")");
}

namespace {

VKAPI_ATTR VkBool32 VKAPI_CALL onValidationMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                   VkDebugUtilsMessageTypeFlagsEXT,
                                                   const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
    if (severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT) {
        std::fprintf(stderr, "penumbra-viewer: Vulkan validation: %s\n", data && data->pMessage ? data->pMessage : "?");
        ++*static_cast<std::atomic<uint32_t>*>(user);
    }
    return VK_FALSE;
}

bool hasExtension(VkPhysicalDevice physicalDevice, const char* name) {
    uint32_t count = 0;
    vkEnumerateDeviceExtensionProperties(physicalDevice, nullptr, &count, nullptr);
    std::vector<VkExtensionProperties> extensions(count);
    vkEnumerateDeviceExtensionProperties(physicalDevice, nullptr, &count, extensions.data());
    return std::any_of(extensions.begin(), extensions.end(),
                       [&](const VkExtensionProperties& e) { return std::strcmp(e.extensionName, name) == 0; });
}

// A queue family with graphics, compute and present to `surface`, or UINT32_MAX.
uint32_t findQueueFamily(VkPhysicalDevice physicalDevice, VkSurfaceKHR surface) {
    uint32_t count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(physicalDevice, &count, nullptr);
    std::vector<VkQueueFamilyProperties> families(count);
    vkGetPhysicalDeviceQueueFamilyProperties(physicalDevice, &count, families.data());
    for (uint32_t i = 0; i < count; ++i) {
        VkBool32 present = VK_FALSE;
        vkGetPhysicalDeviceSurfaceSupportKHR(physicalDevice, i, surface, &present);
        const VkQueueFlags need = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
        if (present && (families[i].queueFlags & need) == need) return i;
    }
    return UINT32_MAX;
}

}  // namespace

VulkanContext::VulkanContext(GLFWwindow* window, const std::string& deviceChoice, bool validation) {
    try {
        createInstance(validation);
        checkVk(glfwCreateWindowSurface(instance, window, nullptr, &surface), "glfwCreateWindowSurface");
        chooseDevice(deviceChoice);
        createDevice();
    } catch (...) {
        release();
        throw;
    }
}

VulkanContext::~VulkanContext() { release(); }

void VulkanContext::release() {
    if (device) vkDestroyDevice(device, nullptr);
    device = VK_NULL_HANDLE;
    if (surface) vkDestroySurfaceKHR(instance, surface, nullptr);
    surface = VK_NULL_HANDLE;
    if (messenger_) {
        auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance, "vkDestroyDebugUtilsMessengerEXT"));
        destroy(instance, messenger_, nullptr);
        messenger_ = VK_NULL_HANDLE;
    }
    if (instance) vkDestroyInstance(instance, nullptr);
    instance = VK_NULL_HANDLE;
}

void VulkanContext::createInstance(bool validation) {
    uint32_t glfwCount = 0;
    const char** glfwExtensions = glfwGetRequiredInstanceExtensions(&glfwCount);
    if (!glfwExtensions) throw Error("no Vulkan device: GLFW finds no Vulkan window-system support");
    std::vector<const char*> extensions(glfwExtensions, glfwExtensions + glfwCount);
    std::vector<const char*> layers;
    if (validation) {
        extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
        layers.push_back("VK_LAYER_KHRONOS_validation");
    }
    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "penumbra-viewer";
    app.pEngineName = "penumbra";
    app.apiVersion = VK_API_VERSION_1_3;
    VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    info.pApplicationInfo = &app;
    info.enabledExtensionCount = uint32_t(extensions.size());
    info.ppEnabledExtensionNames = extensions.data();
    info.enabledLayerCount = uint32_t(layers.size());
    info.ppEnabledLayerNames = layers.data();
    const VkResult result = vkCreateInstance(&info, nullptr, &instance);
    if (result == VK_ERROR_LAYER_NOT_PRESENT)
        throw Error("Vulkan validation requested but VK_LAYER_KHRONOS_validation is not installed");
    if (result != VK_SUCCESS) throw Error("no Vulkan device: vkCreateInstance failed (VkResult " + std::to_string(int(result)) + ")");
    if (!validation) return;
    VkDebugUtilsMessengerCreateInfoEXT messengerInfo{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    messengerInfo.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    messengerInfo.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT;
    messengerInfo.pfnUserCallback = onValidationMessage;
    messengerInfo.pUserData = &messages_;
    auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance, "vkCreateDebugUtilsMessengerEXT"));
    VIEWER_VK(create(instance, &messengerInfo, nullptr, &messenger_));
}

// The devices that can run Penumbra (Vulkan 1.3, push descriptors) and present to the window; auto
// prefers a discrete GPU, then an integrated one, then any GPU, then the CPU (lavapipe).
void VulkanContext::chooseDevice(const std::string& choice) {
    uint32_t count = 0;
    vkEnumeratePhysicalDevices(instance, &count, nullptr);
    std::vector<VkPhysicalDevice> all(count);
    vkEnumeratePhysicalDevices(instance, &count, all.data());
    std::vector<VkPhysicalDevice> usable;
    for (VkPhysicalDevice candidate : all) {
        VkPhysicalDeviceProperties properties;
        vkGetPhysicalDeviceProperties(candidate, &properties);
        if (properties.apiVersion >= VK_API_VERSION_1_3 && hasExtension(candidate, VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME) &&
            hasExtension(candidate, VK_KHR_SWAPCHAIN_EXTENSION_NAME) && findQueueFamily(candidate, surface) != UINT32_MAX)
            usable.push_back(candidate);
    }
    if (usable.empty()) throw Error("no Vulkan device: none with Vulkan 1.3 and push descriptors presents to this window");
    auto typeOf = [&](VkPhysicalDevice d) {
        VkPhysicalDeviceProperties properties;
        vkGetPhysicalDeviceProperties(d, &properties);
        return properties.deviceType;
    };
    auto firstOf = [&](VkPhysicalDeviceType type) {
        auto it = std::find_if(usable.begin(), usable.end(), [&](VkPhysicalDevice d) { return typeOf(d) == type; });
        return it == usable.end() ? VK_NULL_HANDLE : *it;
    };
    if (choice == "auto" || choice == "gpu") {
        for (VkPhysicalDeviceType type : {VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU, VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU,
                                          VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU})
            if (!physicalDevice) physicalDevice = firstOf(type);
        if (!physicalDevice && choice == "auto") physicalDevice = firstOf(VK_PHYSICAL_DEVICE_TYPE_CPU);
        if (!physicalDevice) throw Error("--device gpu: no GPU can render and present to this window");
    } else if (choice == "cpu") {
        physicalDevice = firstOf(VK_PHYSICAL_DEVICE_TYPE_CPU);
        if (!physicalDevice) throw Error("--device cpu: no CPU Vulkan device (mesa-vulkan-drivers' lavapipe)");
    } else {
        const bool digits = !choice.empty() && choice.size() < 6 &&
                            std::all_of(choice.begin(), choice.end(), [](char c) { return c >= '0' && c <= '9'; });
        if (!digits || std::stoul(choice) >= usable.size())
            throw Error("--device " + choice + ": expected auto, gpu, cpu or an index below " + std::to_string(usable.size()));
        physicalDevice = usable[std::stoul(choice)];
    }
    VkPhysicalDeviceProperties properties;
    vkGetPhysicalDeviceProperties(physicalDevice, &properties);
    deviceName = properties.deviceName;
    queueFamily = findQueueFamily(physicalDevice, surface);
}

// The features and extensions <penumbra/vulkan.h> lists, plus the swapchain.
void VulkanContext::createDevice() {
    VkPhysicalDeviceFeatures supported{};
    vkGetPhysicalDeviceFeatures(physicalDevice, &supported);
    VkPhysicalDeviceVulkan13Features features13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    features13.dynamicRendering = features13.synchronization2 = features13.maintenance4 = VK_TRUE;
    VkPhysicalDeviceVulkan12Features features12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
    features12.pNext = &features13;
    features12.drawIndirectCount = VK_TRUE;
    // Optional: the visibility-buffer main view (render.mainView).
    VkPhysicalDeviceVulkan12Features supported12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
    VkPhysicalDeviceFeatures2 supportedAll{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    supportedAll.pNext = &supported12;
    vkGetPhysicalDeviceFeatures2(physicalDevice, &supportedAll);
    bufferInt64Atomics = supported.shaderInt64 && supported12.shaderBufferInt64Atomics;
    features12.shaderBufferInt64Atomics = bufferInt64Atomics;
    VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    features.pNext = &features12;
    features.features.depthClamp = VK_TRUE;
    features.features.shaderStorageImageWriteWithoutFormat = supported.shaderStorageImageWriteWithoutFormat;
    features.features.fragmentStoresAndAtomics = supported.fragmentStoresAndAtomics;
    features.features.shaderInt64 = bufferInt64Atomics;
    uint32_t penumbraCount = 0;
    const char* const* penumbraExtensions = requiredVulkanDeviceExtensions(&penumbraCount);
    std::vector<const char*> extensions(penumbraExtensions, penumbraExtensions + penumbraCount);
    extensions.push_back(VK_KHR_SWAPCHAIN_EXTENSION_NAME);
    const float priority = 1.0f;
    VkDeviceQueueCreateInfo queueInfo{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    queueInfo.queueFamilyIndex = queueFamily;
    queueInfo.queueCount = 1;
    queueInfo.pQueuePriorities = &priority;
    VkDeviceCreateInfo info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
    info.pNext = &features;
    info.queueCreateInfoCount = 1;
    info.pQueueCreateInfos = &queueInfo;
    info.enabledExtensionCount = uint32_t(extensions.size());
    info.ppEnabledExtensionNames = extensions.data();
    VIEWER_VK(vkCreateDevice(physicalDevice, &info, nullptr, &device));
    vkGetDeviceQueue(device, queueFamily, 0, &queue);
}

uint32_t VulkanContext::memoryType(uint32_t typeBits, VkMemoryPropertyFlags flags) const {
    VkPhysicalDeviceMemoryProperties properties;
    vkGetPhysicalDeviceMemoryProperties(physicalDevice, &properties);
    for (uint32_t i = 0; i < properties.memoryTypeCount; ++i)
        if ((typeBits & (1u << i)) && (properties.memoryTypes[i].propertyFlags & flags) == flags) return i;
    throw Error("no Vulkan memory type with the flags the viewer needs");
}

VkImage VulkanContext::createImage(VkFormat format, VkExtent2D extent, VkImageUsageFlags usage,
                                   VkDeviceMemory* memory) const {
    VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    info.imageType = VK_IMAGE_TYPE_2D;
    info.format = format;
    info.extent = {extent.width, extent.height, 1};
    info.mipLevels = info.arrayLayers = 1;
    info.samples = VK_SAMPLE_COUNT_1_BIT;
    info.usage = usage;
    VkImage image = VK_NULL_HANDLE;
    VIEWER_VK(vkCreateImage(device, &info, nullptr, &image));
    VkMemoryRequirements requirements;
    vkGetImageMemoryRequirements(device, image, &requirements);
    VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    alloc.allocationSize = requirements.size;
    alloc.memoryTypeIndex = memoryType(requirements.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    const VkResult result = vkAllocateMemory(device, &alloc, nullptr, memory);
    if (result != VK_SUCCESS) vkDestroyImage(device, image, nullptr);
    checkVk(result, "vkAllocateMemory");
    VIEWER_VK(vkBindImageMemory(device, image, *memory, 0));
    return image;
}

VkBuffer VulkanContext::createHostBuffer(VkDeviceSize bytes, VkBufferUsageFlags usage, VkDeviceMemory* memory) const {
    VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    info.size = bytes;
    info.usage = usage;
    VkBuffer buffer = VK_NULL_HANDLE;
    VIEWER_VK(vkCreateBuffer(device, &info, nullptr, &buffer));
    VkMemoryRequirements requirements;
    vkGetBufferMemoryRequirements(device, buffer, &requirements);
    VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    alloc.allocationSize = requirements.size;
    alloc.memoryTypeIndex = memoryType(requirements.memoryTypeBits,
                                       VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
    const VkResult result = vkAllocateMemory(device, &alloc, nullptr, memory);
    if (result != VK_SUCCESS) vkDestroyBuffer(device, buffer, nullptr);
    checkVk(result, "vkAllocateMemory");
    VIEWER_VK(vkBindBufferMemory(device, buffer, *memory, 0));
    return buffer;
}

}  // namespace penumbra::viewer
