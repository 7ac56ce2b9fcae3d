// `penumbra bench`, the instrument of docs/performance.md: its JSON carries every documented key,
// and a steady-state frame makes no GPU object.
#include <sched.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_process.h"

namespace penumbra::test {
namespace {

nlohmann::json runBenchJson(const std::string& arguments) {
    const std::string path =
        (std::filesystem::temp_directory_path() / ("penumbra_bench_" + std::to_string(::getpid()) + ".json")).string();
    const CliRun run = runPenumbra("bench --device cpu --validation --width 64 --height 48 --json " + path + " " + arguments);
    EXPECT_EQ(run.exitCode, 0) << run.err;
    std::ifstream file(path);
    EXPECT_TRUE(file.good()) << "no JSON written: " << run.out << run.err;
    if (!file) return {};
    nlohmann::json json = nlohmann::json::parse(file, nullptr, false);
    std::filesystem::remove(path);
    return json;
}

void expectStatistics(const nlohmann::json& entry, const std::vector<std::string>& keys, const std::string& where) {
    for (const std::string& key : keys) {
        ASSERT_TRUE(entry.contains(key)) << where << " lacks " << key;
        EXPECT_TRUE(entry[key].is_number()) << where << "." << key;
        EXPECT_GE(entry[key].get<double>(), 0.0) << where << "." << key;
    }
}

TEST(CliBench, JsonHasEveryDocumentedKey) {
    const nlohmann::json json = runBenchJson("--frames 4 --warmup 1 --camera orbit");
    ASSERT_TRUE(json.is_object());
    EXPECT_TRUE(json["device"].is_string());
    EXPECT_EQ(json["width"], 64);
    EXPECT_EQ(json["height"], 48);
    EXPECT_EQ(json["frames"], 4);
    EXPECT_GT(json["scene"]["triangles"].get<uint64_t>(), 1000u);
    EXPECT_EQ(json["scene"]["instances"], 13);
    EXPECT_EQ(json["scene"]["lights"], 3);
    for (const char* pass : {"shadows.directional", "shadows.other", "main"}) {
        ASSERT_TRUE(json["passes"].contains(pass)) << pass;
        expectStatistics(json["passes"][pass], {"median_ms", "p95_ms", "min_ms"}, pass);
        EXPECT_LE(json["passes"][pass]["min_ms"].get<double>(), json["passes"][pass]["median_ms"].get<double>());
    }
    for (const char* phase : {"plan", "culling", "upload", "record", "submit", "readback", "total"}) {
        ASSERT_TRUE(json["cpu"].contains(phase)) << phase;
        expectStatistics(json["cpu"][phase], {"median_ms", "p95_ms"}, phase);
    }
    // The total is its own series: at least each phase's median (every frame's sum holds every phase).
    for (const char* phase : {"plan", "culling", "upload", "record", "submit", "readback"})
        EXPECT_GE(json["cpu"]["total"]["median_ms"].get<double>(), json["cpu"][phase]["median_ms"].get<double>()) << phase;
    expectStatistics(json["frame"], {"median_ms", "p95_ms"}, "frame");
    EXPECT_GT(json["frame"]["median_ms"].get<double>(), 0.0);
    // GPU timestamps of whole frames (lavapipe has them): commands first to last, and the period.
    expectStatistics(json["gpuFrame"], {"median_ms", "p95_ms"}, "gpuFrame");
    expectStatistics(json["gpuFramePeriod"], {"median_ms", "p95_ms"}, "gpuFramePeriod");
    EXPECT_GE(json["gpuFrame"]["median_ms"].get<double>(), json["passes"]["main"]["median_ms"].get<double>());
    EXPECT_GE(json["gpuFramePeriod"]["median_ms"].get<double>(), json["gpuFrame"]["median_ms"].get<double>() * 0.99);
    for (const char* memory : {"host_rss_mb", "device_mb"}) expectStatistics(json["memory"][memory], {"first", "last"}, memory);
    EXPECT_GT(json["memory"]["host_rss_mb"]["first"].get<double>(), 1.0);
    EXPECT_GT(json["atlases"]["shadows.directional"]["draws"].get<uint32_t>(), 0u);
    EXPECT_EQ(json["validationMessages"], 0);
    for (const char* key : {"rendered", "reused"}) EXPECT_TRUE(json["tiles"][key].is_number()) << key;
    EXPECT_EQ(json["shadowRaster"]["dropped"], 0);
    for (const char* key : {"mean", "max"}) EXPECT_TRUE(json["lightsPerCluster"][key].is_number()) << key;
    for (const char* key : {"instances", "drawnEarly", "drawnLate", "triangles"})
        EXPECT_TRUE(json["mainView"][key].is_number()) << key;
}

TEST(CliBench, ReportsTheVisibilityBuffersCulling) {
    const nlohmann::json json =
        runBenchJson("--frames 3 --warmup 2 --camera static --main-view visibility --set render.viewCulling=frustum");
    ASSERT_TRUE(json.is_object());
    EXPECT_EQ(json["mainView"]["used"], "visibility");
    EXPECT_GT(json["mainView"]["drawnEarly"].get<double>(), 0.0);
    EXPECT_LE(json["mainView"]["drawnEarly"].get<double>(), json["mainView"]["instances"].get<double>());
    EXPECT_EQ(json["mainView"]["drawnLate"].get<double>(), 0.0);  // frustum culling has no late phase
    EXPECT_GT(json["mainView"]["triangles"].get<double>(), 0.0);
}

TEST(CliBench, SteadyStateFramesMakeNoGpuObject) {
    const nlohmann::json json = runBenchJson("--frames 6 --warmup 2 --camera orbit");
    ASSERT_TRUE(json.is_object());
    EXPECT_EQ(json["allocationsAfterWarmup"]["gpuObjects"], 0);
    EXPECT_EQ(json["allocationsAfterWarmup"]["vkAllocateMemory"], 0);
}

TEST(CliBench, PrintsATableOfPassesPhasesAndMemory) {
    const CliRun run = runPenumbra("bench --frames 2 --warmup 1 --width 64 --height 48 --device cpu");
    ASSERT_EQ(run.exitCode, 0) << run.err;
    for (const char* line : {"gpu main", "gpu shadows.directional", "cpu plan", "cpu culling", "frame (submit to fence)",
                             "frame (GPU, first to last)", "frame period (GPU end to end)", "host RSS", "after warm-up: 0 GPU objects made"})
        EXPECT_NE(run.out.find(line), std::string::npos) << line << " missing from:\n" << run.out;
    // Not a terminal: no progress bar.
    EXPECT_EQ(run.out.find('\r'), std::string::npos);
}

TEST(CliBench, StillCameraReusesEveryShadowTile) {
    const nlohmann::json json = runBenchJson("--frames 4 --warmup 2 --camera static");
    ASSERT_TRUE(json.is_object());
    EXPECT_EQ(json["tiles"]["rendered"], 0);
    EXPECT_EQ(json["tiles"]["reused"], 6);  // 4 cascades and 2 spot tiles
    // Nothing moves without --light-motion and --move-objects.
    EXPECT_EQ(json["lightMotion"]["degreesPerFrame"], 0);
    EXPECT_EQ(json["lightMotion"]["lights"], 0);
    EXPECT_EQ(json["moveObjects"]["fraction"], 0);
    EXPECT_EQ(json["moveObjects"]["moved"], 0);
}

TEST(CliBench, LightMotionTurnsTheSunSoItsCascadesAreDrawnEveryFrame) {
    const nlohmann::json json = runBenchJson("--frames 4 --warmup 1 --camera static --light-motion 5");
    ASSERT_TRUE(json.is_object());
    EXPECT_EQ(json["lightMotion"]["degreesPerFrame"], 5);
    EXPECT_EQ(json["lightMotion"]["lights"], 1);  // the demo's sun; its 2 spots stay
    // A still camera: the turned sun's 4 cascades are drawn again in every timed frame, the spot
    // tiles are reused (a still scene reuses all 6: StillCameraReusesEveryShadowTile).
    EXPECT_EQ(json["tiles"]["renderedMin"], 4);
    EXPECT_EQ(json["tiles"]["rendered"], 4);
    EXPECT_EQ(json["tiles"]["reused"], 2);
    EXPECT_EQ(json["validationMessages"], 0);
}

TEST(CliBench, MoveObjectsMovesThatShareOfTheInstancesEveryFrame) {
    const nlohmann::json json = runBenchJson("--frames 4 --warmup 1 --camera static --move-objects 0.5");
    ASSERT_TRUE(json.is_object());
    EXPECT_EQ(json["moveObjects"]["fraction"], 0.5);
    EXPECT_EQ(json["moveObjects"]["moved"], 7);  // ceil(0.5 x 13)
    EXPECT_EQ(json["lightMotion"]["lights"], 0);
    // Moved casters: every tile is drawn again in every timed frame, and no GPU object is made.
    EXPECT_EQ(json["tiles"]["renderedMin"], 6);
    EXPECT_EQ(json["tiles"]["reused"], 0);
    EXPECT_EQ(json["allocationsAfterWarmup"]["gpuObjects"], 0);
    EXPECT_EQ(json["validationMessages"], 0);
    // 0.28 x 25 is 7.000000000000001 in binary: still 7 of 24 boxes and the ground.
    EXPECT_EQ(runBenchJson("gen:boxes:24 --frames 1 --warmup 0 --move-objects 0.28")["moveObjects"]["moved"], 7);
}

// The CPUs this test process may run on (the bench inherits them).
std::vector<int> allowedCpus() {
    cpu_set_t set;
    CPU_ZERO(&set);
    std::vector<int> cpus;
    if (sched_getaffinity(0, sizeof(set), &set) != 0) return cpus;
    for (int cpu = 0; cpu < CPU_SETSIZE; ++cpu)
        if (CPU_ISSET(cpu, &set)) cpus.push_back(cpu);
    return cpus;
}

TEST(CliBench, PinCpuKeepsTheFrameThreadOnThatCpu) {
    const std::vector<int> cpus = allowedCpus();
    if (cpus.size() < 2) GTEST_SKIP() << "one CPU: pinned and unpinned threads look alike";
    const int cpu = cpus.back();
    const nlohmann::json pinned = runBenchJson("--frames 6 --warmup 1 --pin-cpu " + std::to_string(cpu))["frameThread"];
    EXPECT_EQ(pinned["pinnedCpu"], cpu);
    EXPECT_EQ(pinned["allowedCpus"], 1);
    EXPECT_EQ(pinned["cpusSeen"], 1);
    EXPECT_EQ(pinned["migrations"], 0);
    // Unpinned, the frame thread may use every CPU the process may.
    const nlohmann::json free = runBenchJson("--frames 2 --warmup 1")["frameThread"];
    EXPECT_EQ(free["pinnedCpu"], -1);
    EXPECT_EQ(free["allowedCpus"], int(cpus.size()));
    EXPECT_GE(free["cpusSeen"].get<int>(), 1);
}

TEST(CliBench, PrintsTheMotionInTheHeader) {
    const CliRun run = runPenumbra(
        "bench --frames 1 --warmup 0 --width 64 --height 48 --device cpu --light-motion 2.5 --move-objects 1");
    ASSERT_EQ(run.exitCode, 0) << run.err;
    EXPECT_NE(run.out.find("camera static, light motion 2.5 deg/frame (1 directional light), move objects 1 (13 of 13 "
                           "instances per frame)\n"),
              std::string::npos)
        << run.out;
    // Without them the header line ends at the camera.
    const CliRun still = runPenumbra("bench --frames 1 --warmup 0 --width 64 --height 48 --device cpu");
    ASSERT_EQ(still.exitCode, 0) << still.err;
    EXPECT_NE(still.out.find("camera static\n"), std::string::npos) << still.out;
}

TEST(CliBench, MeasuresTheBuiltInBoxesScene) {
    const nlohmann::json json = runBenchJson("gen:boxes:300 --frames 2 --warmup 1");
    ASSERT_TRUE(json.is_object());
    EXPECT_EQ(json["scene"]["instances"], 301);  // 300 boxes and the ground
    EXPECT_EQ(json["scene"]["triangles"], 300 * 12 + 2);
}

TEST(CliBench, VarySettingsChangesSettingsAndShadowedLightsEveryPeriodAndSamplesMemory) {
    const nlohmann::json json = runBenchJson("--frames 16 --warmup 1 --vary-settings --vary-every 4");
    ASSERT_TRUE(json.is_object());
    const nlohmann::json& vary = json["vary"];
    EXPECT_EQ(vary["period"], 4);
    ASSERT_EQ(vary["samples"].size(), 4u);
    std::set<int> shadowed;
    for (size_t i = 0; i < 4; ++i) {
        EXPECT_EQ(vary["samples"][i]["frame"], 4 * (i + 1));
        EXPECT_EQ(vary["samples"][i]["step"], i);
        shadowed.insert(vary["samples"][i]["shadowedLights"].get<int>());
        EXPECT_GT(vary["samples"][i]["host_rss_mb"].get<double>(), 1.0);
    }
    EXPECT_GE(shadowed.size(), 3u);  // the demo's 3 lights: 3, 2, 1, 0 shadowed
    for (const char* memory : {"host_rss_mb", "device_mb"})
        expectStatistics(vary[memory], {"first", "last", "max", "growth"}, memory);
    EXPECT_EQ(json["validationMessages"], 0);
    // The atlases were made again for the new sizes: those frames did allocate.
    EXPECT_GT(json["allocationsAfterWarmup"]["gpuObjects"].get<int>(), 0);
}

TEST(CliBench, WithoutVarySettingsThereIsNoVaryBlock) {
    EXPECT_FALSE(runBenchJson("--frames 2 --warmup 1").contains("vary"));
}

// --frame-times: a header and one row per timed frame (none for the warm-up frames still in flight when
// the timed ones start), each frame's CPU total the sum of its phases, its thread time (plan to
// submit, CPU time of one thread) above zero and no more than the wall time of those phases, give or
// take 0.05 ms: the thread clock is read by a system call, four a frame, which a busy 2-core machine
// can make ten microseconds slow (1 frame in 40 exceeded the wall time by 0.010 ms under ctest -j2).
TEST(CliBench, FrameTimesWritesOneCsvRowPerTimedFrame) {
    const std::string path =
        (std::filesystem::temp_directory_path() / ("penumbra_frames_" + std::to_string(::getpid()) + ".csv")).string();
    const CliRun run = runPenumbra("bench --device cpu --width 64 --height 48 --frames 5 --warmup 3 --camera orbit --frame-times " + path);
    ASSERT_EQ(run.exitCode, 0) << run.err;
    std::ifstream file(path);
    std::string line;
    ASSERT_TRUE(std::getline(file, line));
    EXPECT_EQ(line, "frame,gpuFrameMs,submitToFenceMs,cpu_planMs,cpu_cullingMs,cpu_uploadMs,cpu_recordMs,cpu_submitMs,cpu_readbackMs,"
                    "cpu_totalMs,cpu_threadMs");
    int rows = 0;
    while (std::getline(file, line)) {
        std::vector<double> cells;
        std::stringstream row(line);
        for (std::string cell; std::getline(row, cell, ',');) cells.push_back(std::stod(cell));
        ASSERT_EQ(cells.size(), 11u) << line;
        EXPECT_EQ(cells[0], rows);
        EXPECT_NEAR(cells[9], cells[3] + cells[4] + cells[5] + cells[6] + cells[7] + cells[8], 6e-4) << line;
        EXPECT_GT(cells[10], 0.0) << line;
        EXPECT_LE(cells[10], cells[3] + cells[4] + cells[5] + cells[6] + cells[7] + 0.05) << line;
        ++rows;
    }
    EXPECT_EQ(rows, 5);
    std::filesystem::remove(path);
}

TEST(CliBench, FrameTimesDashPrintsTheCsvAfterTheReport) {
    const CliRun run = runPenumbra("bench --device cpu --width 64 --height 48 --frames 3 --warmup 1 --frame-times -");
    ASSERT_EQ(run.exitCode, 0) << run.err;
    const size_t header = run.out.find("frame,gpuFrameMs,");
    ASSERT_NE(header, std::string::npos) << run.out;
    EXPECT_GT(header, run.out.find("validation messages")) << "the CSV follows the report";
    EXPECT_NE(run.out.find("\n2,", header), std::string::npos) << "rows 0, 1, 2";
    EXPECT_FALSE(std::filesystem::exists("-"));
}

TEST(CliBench, RejectsAnUnknownCameraMode) {
    const CliRun run = runPenumbra("bench --camera sideways --device cpu");
    EXPECT_EQ(run.exitCode, 1);
}

}  // namespace
}  // namespace penumbra::test
