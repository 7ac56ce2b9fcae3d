#include "render/virtual_face_shadows.h"

#include <algorithm>
#include <cmath>

#include "pass_bindings.h"
#include "render/virtual_shadows.h"
#include "shadows/virtual_page_pool.h"
#include "shadows/virtual_shadow_lookup.h"

namespace penumbra {

namespace {

constexpr uint32_t kMaxFaces = gpu_data::kMaxOtherShadowTiles;

}  // namespace

VirtualFaceShadows::SlotLayout VirtualFaceShadows::slotLayout() {
    SlotLayout layout;
    layout.lit = 0;
    layout.mark = layout.lit + gpu::portablyAligned(sizeof(gpu_data::VirtualFaceShadowData));
    layout.faces = layout.mark + gpu::portablyAligned(sizeof(gpu_data::VirtualFaceMarkData));
    layout.lights = layout.faces + gpu::portablyAligned(kMaxFaces * sizeof(gpu_data::VirtualFaceData));
    layout.table = layout.lights + gpu::portablyAligned(kMaxFaces * sizeof(gpu_data::VirtualFaceLightData));
    layout.invalidations = layout.table + gpu::portablyAligned(sizeof(gpu_data::VirtualPageTableData));
    layout.size = layout.invalidations + gpu::portablyAligned(kMaxInvalidations * sizeof(gpu_data::VirtualPageInvalidation));
    return layout;
}

VirtualFaceShadows::VirtualFaceShadows(gpu::Device& device, const GpuScene& gpuScene, ComputeRasterPass& raster)
    : device_(device), scene_(gpuScene), raster_(raster) {
    slotCount_ = device.framesInFlight() + 1;  // a slot is free again once its next frame begins
    try {
        uploads_ = device.createBuffer(slotLayout().size * slotCount_, gpu::kBufferUniform | gpu::kBufferStorage,
                                       gpu::MemoryKind::HostVisible, nullptr, "virtual face uploads");
        placeholderPool_ = device.createTexture({1, 1, gpu::Format::R32Float, gpu::kTextureSampled, 1, "no virtual face pool"});
        placeholderPages_ = device.createBuffer(sizeof(gpu_data::VirtualPageEntry), gpu::kBufferStorage,
                                                gpu::MemoryKind::DeviceLocal, nullptr, "no virtual face page table");
    } catch (...) {  // the destructor does not run
        device.destroy(uploads_);
        device.destroy(placeholderPool_);
        throw;
    }
    faces_.reserve(kMaxFaces);
    drawnFaces_.reserve(kMaxFaces);
    changedBounds_.reserve(kMaxInvalidations);
}

VirtualFaceShadows::~VirtualFaceShadows() {
    draw_.reset();
    table_.reset();
    mark_.reset();
    device_.destroy(uploads_);
    device_.destroy(placeholderPool_);
    device_.destroy(placeholderPages_);
}

bool VirtualFaceShadows::notePoolLoad(const VirtualPageCounts& pages) {
    // Only a frame marked at the current steps and with this pool tells their load (frames in flight
    // recorded before the last change do not step twice).
    if (pages.poolPages == 0 || pages.poolPages != config_.poolSide * config_.poolSide || pages.lodBiasSteps != pressureSteps_)
        return false;
    const uint32_t before = pressureSteps_;
    pressureSteps_ = nextPoolPressureSteps(pressureSteps_, {pages.requested, pages.overflowed, pages.poolPages});
    return pressureSteps_ > before;
}

void VirtualFaceShadows::configure(const Config& config) {
    if (table_ && config == config_) return;
    draw_.reset();  // deferred by the device until the frames using them are done
    table_.reset();
    if (config.poolSide != config_.poolSide) pressureSteps_ = 0;  // a new pool's load is not known yet
    config_ = config;
    if (config.faceCount == 0) return;
    if (!mark_) mark_ = std::make_unique<VirtualFaceMarkPass>(device_);
    table_ = std::make_unique<VirtualPageTablePass>(device_, virtualFaceTableLayout(config.faces, config.faceCount),
                                                    config.poolSide * config.poolSide, config.keepFrames);
    draw_ = std::make_unique<VirtualPageDrawPass>(device_, scene_, raster_, config.faces, config.poolSide);
    drawnFaces_.clear();  // every face is new: the table starts empty
}

void VirtualFaceShadows::beginFrame(const ShadowSettings& settings, const OtherShadowPlan& plan, const ShadowRasterOptions& raster,
                                    const CameraView& view, std::vector<std::string>& warnings) {
    active_ = plan.virtualFaces && !plan.faces.empty();
    const SlotLayout layout = slotLayout();
    slot_ = (slot_ + 1) % slotCount_;
    const uint64_t base = uint64_t(slot_) * layout.size;
    gpu_data::VirtualFaceShadowData block{};
    if (active_) {
        Config config;
        config.faces = plan.faceConfig;
        config.faceCount = uint32_t(std::min<size_t>(plan.faces.size(), kMaxFaces));
        config.keepFrames = settings.virtualMaps.keepFrames;
        const uint32_t requested = virtualPoolPagesPerSide(settings.virtualMaps.facePoolPages);
        config.poolSide = fitVirtualPool(requested, config.faces.pageSize, 1, device_.maxImageSize());
        if (config.poolSide < requested)
            warnings.push_back("shadows.virtual.facePoolPages = " + std::to_string(settings.virtualMaps.facePoolPages) +
                               " for the spot and point lights' faces is more than " + device_.info().name +
                               " holds; using " + std::to_string(config.poolSide * config.poolSide) + " pages");
        configure(config);
        if (!settings.virtualMaps.cache) invalidateAll_ = true;
        table_->setDrawBudget(virtualDrawBudget(settings.virtualMaps.pagesPerFrame, draw_->pagesPerRecord()));
        lightCount_ = uint32_t(std::min<size_t>(plan.faceLights.size(), kMaxFaces));
        if (raster.lodErrorTexels != rasterOptions_.lodErrorTexels) invalidateAll_ = true;  // pages drawn with other levels
        rasterOptions_ = raster;
        footprintScale_ = std::exp2(settings.virtualMaps.faceLodBias + float(pressureSteps_));
        marginTexels_ = plan.faceMarginTexels;
        faces_.assign(plan.faces.begin(), plan.faces.begin() + config_.faceCount);
        block.enabled = 1u;
        block.wsFootprintPerDepth = wsFootprintPerDepth(view) * footprintScale_;  // the marking pass's
        block.table = packVirtualFaceLookup(config_.faces, config_.faceCount, config_.poolSide);
        std::array<gpu_data::VirtualFaceLightData, kMaxFaces> lights{};
        for (uint32_t face = 0; face < config_.faceCount; ++face) block.faces[face] = packVirtualFace(faces_[face]);
        for (uint32_t light = 0; light < lightCount_; ++light)
            lights[light] = {plan.faceLights[light].firstFace, plan.faceLights[light].point ? 1u : 0u, 0u, 0u};
        device_.writeBuffer(uploads_, block.faces, config_.faceCount * sizeof(block.faces[0]), base + layout.faces);
        device_.writeBuffer(uploads_, lights.data(), lightCount_ * sizeof(lights[0]), base + layout.lights);
    } else if (table_) {
        configure(Config{});  // the atlas, or no light: the table and pool go
        changedBounds_.clear();
    }
    device_.writeBuffer(uploads_, &block, sizeof(block), base + layout.lit);
}

void VirtualFaceShadows::appendLitInputs(MainPassInputs& inputs, gpu::SamplerHandle pointSampler) const {
    using namespace gpu_data;
    const bool bound = active_ && draw_;
    const gpu::TextureHandle pool = bound ? draw_->poolTexture() : placeholderPool_;
    const gpu::BufferHandle pages = bound ? table_->entries() : placeholderPages_;
    const uint64_t base = uint64_t(slot_) * slotLayout().size;
    appendVirtualLitInputs(inputs, {kLitBindingVirtualFaces, kLitBindingVirtualFacePool, kLitBindingVirtualFacePages, 1},
                           {uploads_, base, sizeof(VirtualFaceShadowData)}, pool, pages, pointSampler);
}

void VirtualFaceShadows::casterChanged(const Aabb& wsBounds) {
    if (!active_ || !wsBounds.valid()) return;
    if (changedBounds_.size() >= kMaxInvalidations) {  // too many to track: redraw all
        invalidateAll_ = true;
        return;
    }
    changedBounds_.push_back(wsBounds);
}

bool VirtualFaceShadows::collectInvalidations() {
    invalidationCount_ = 0;
    const uint32_t mips = virtualFaceMipCount(config_.faces);
    const auto add = [&](uint32_t level, const PageRect& pages) {
        if (invalidationCount_ >= invalidations_.size()) return false;
        invalidations_[invalidationCount_++] = virtualPageInvalidation(level, pages);
        return true;
    };
    for (uint32_t face = 0; face < config_.faceCount; ++face) {
        if (face < drawnFaces_.size() && drawnFaces_[face] == faces_[face].clipFromWorld) continue;
        for (uint32_t mip = 0; mip < mips; ++mip) {  // a new projection: every page of the face
            const int32_t last = int32_t(virtualFacePagesPerSide(config_.faces) >> mip) - 1;
            if (!add(virtualFaceLevel(mip, face, config_.faceCount), PageRect{glm::ivec2(0), glm::ivec2(last)})) return false;
        }
    }
    for (const Aabb& bounds : changedBounds_)
        for (uint32_t face = 0; face < config_.faceCount; ++face) {
            const uint32_t count = casterFacePageRects(config_.faces, faces_[face], face, config_.faceCount, bounds, mipRects_.data());
            for (uint32_t i = 0; i < count; ++i)
                if (!add(mipRects_[i].level, mipRects_[i].pages)) return false;
        }
    return true;
}

void VirtualFaceShadows::record(gpu::CommandList& commands, const VirtualPageDepthSource& depth, const CameraView& view,
                                uint64_t& rasterReadback) {
    if (!active_ || !table_) return;
    const bool invalidateAll = invalidateAll_ || !collectInvalidations();
    if (invalidateAll) invalidationCount_ = 0;
    invalidateAll_ = false;
    changedBounds_.clear();
    drawnFaces_.resize(config_.faceCount);
    for (uint32_t face = 0; face < config_.faceCount; ++face) drawnFaces_[face] = faces_[face].clipFromWorld;

    const SlotLayout layout = slotLayout();
    const uint64_t base = uint64_t(slot_) * layout.size;
    const gpu_data::VirtualFaceMarkData mark =
        packVirtualFaceMark(config_.faces, view, config_.faceCount, lightCount_, marginTexels_, footprintScale_);
    const gpu_data::VirtualPageTableData tableData = table_->packFrame(glm::vec2(0.0f), invalidateAll, invalidationCount_);
    device_.writeBuffer(uploads_, &mark, sizeof(mark), base + layout.mark);
    device_.writeBuffer(uploads_, &tableData, sizeof(tableData), base + layout.table);
    if (invalidationCount_ > 0)
        device_.writeBuffer(uploads_, invalidations_.data(), invalidationCount_ * sizeof(invalidations_[0]),
                            base + layout.invalidations);
    const gpu::BufferSlice faces{uploads_, base + layout.faces, config_.faceCount * sizeof(gpu_data::VirtualFaceData)};
    // 1. Marking, 2. the table update, 3. drawing the dirty pages, 4. marking them drawn.
    commands.beginTimer("virtualFaces/mark");
    mark_->record(commands, depth,
                 {{uploads_, base + layout.mark, sizeof(mark)}, faces,
                  {uploads_, base + layout.lights, lightCount_ * sizeof(gpu_data::VirtualFaceLightData)}},
                 virtualFaceTableLayout(config_.faces, config_.faceCount));
    commands.endTimer();
    commands.beginTimer("virtualFaces/table");
    table_->record(commands, {mark_->requestWords(), {uploads_, base + layout.table, sizeof(tableData)},
                              {uploads_, base + layout.invalidations, kMaxInvalidations * sizeof(gpu_data::VirtualPageInvalidation)},
                              invalidationCount_});
    commands.endTimer();
    VirtualPageDrawInputs inputs{table_->drawList(), table_->entriesSlice(), nullptr, rasterOptions_, faces, config_.faceCount};
    commands.beginTimer("virtualFaces/draw");
    draw_->record(commands, inputs);
    commands.endTimer();
    rasterReadback = device_.readBackAtFrameEnd(commands, raster_.counters());
    commands.beginTimer("virtualFaces/drawn");
    table_->recordMarkDrawn(commands);
    commands.endTimer();
}

}  // namespace penumbra
