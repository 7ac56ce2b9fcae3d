#pragma once
// Everything a program needs to render with Penumbra without touching Vulkan: load a scene (a glTF
// file, the demo scene, a built-in scale scene, or one built in memory), settings (parse, validate,
// override by dotted key), a device, and a renderer that renders frames and reads them back.
// <penumbra/vulkan.h> adds rendering into the caller's own VkImage on the caller's VkDevice.
#include <penumbra/camera.h>
#include <penumbra/device.h>
#include <penumbra/error.h>
#include <penumbra/image.h>
#include <penumbra/renderer.h>
#include <penumbra/scene.h>
#include <penumbra/scene_builder.h>
#include <penumbra/scene_loading.h>
#include <penumbra/settings.h>
#include <penumbra/settings_keys.h>
