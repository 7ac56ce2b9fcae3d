#include "viewer/camera_path.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "penumbra/files.h"
#include "penumbra/error.h"

namespace penumbra::viewer {

namespace {

using nlohmann::json;

// The numbers of `field` of keyframe `index` (an array of `count` finite numbers).
std::vector<float> numbers(const json& keyframe, const char* field, size_t count, const std::string& where) {
    const auto found = keyframe.find(field);
    if (found == keyframe.end()) throw Error(where + " has no \"" + field + "\"");
    if (!found->is_array() || found->size() != count)
        throw Error(where + "." + field + " must be an array of " + std::to_string(count) + " numbers");
    std::vector<float> values;
    for (const json& value : *found) {
        if (!value.is_number() || !std::isfinite(value.get<double>()))
            throw Error(where + "." + field + " must be an array of " + std::to_string(count) + " numbers");
        values.push_back(value.get<float>());
    }
    return values;
}

CameraKeyframe parseKeyframe(const json& keyframe, const std::string& where) {
    if (!keyframe.is_object()) throw Error(where + " must be an object");
    CameraKeyframe key;
    const auto time = keyframe.find("time");
    if (time == keyframe.end() || !time->is_number() || !std::isfinite(time->get<double>()))
        throw Error(where + ".time must be a number (seconds)");
    key.time = time->get<float>();
    const std::vector<float> p = numbers(keyframe, "position", 3, where);
    key.wsPosition = glm::vec3(p[0], p[1], p[2]);
    const std::vector<float> r = numbers(keyframe, "rotation", 4, where);  // x, y, z, w as in glTF
    key.rotation = glm::quat(r[3], r[0], r[1], r[2]);
    const float length = glm::length(key.rotation);
    if (!(length > 1e-6f)) throw Error(where + ".rotation must be a non-zero quaternion [x, y, z, w]");
    key.rotation /= length;
    if (const auto yfov = keyframe.find("yfov"); yfov != keyframe.end()) {
        if (!yfov->is_number() || !(yfov->get<double>() > 0.0 && yfov->get<double>() < M_PI))
            throw Error(where + ".yfov must be a number in (0, pi) (radians)");
        key.yfov = yfov->get<float>();
    }
    return key;
}

Camera cameraOf(const CameraKeyframe& key, const Camera& base) {
    Camera camera = base;
    camera.worldFromView = glm::mat4_cast(key.rotation);
    camera.worldFromView[3] = glm::vec4(key.wsPosition, 1.0f);
    camera.yfov = key.yfov;
    return camera;
}

}  // namespace

CameraPath parseCameraPath(const std::string& text, const std::string& name) {
    const json root = json::parse(text, nullptr, false);
    if (root.is_discarded()) throw Error("camera path " + name + " is not valid JSON");
    const std::string prefix = "camera path " + name + ": ";
    if (!root.is_object() || !root.contains("keyframes") || !root["keyframes"].is_array())
        throw Error(prefix + "expected an object with an array \"keyframes\"");
    CameraPath path;
    for (size_t i = 0; i < root["keyframes"].size(); ++i) {
        const std::string where = "keyframes[" + std::to_string(i) + "]";
        try {
            path.keyframes.push_back(parseKeyframe(root["keyframes"][i], where));
        } catch (const Error& error) {
            throw Error(prefix + error.what());
        }
        if (i > 0 && !(path.keyframes[i].time > path.keyframes[i - 1].time))
            throw Error(prefix + where + ".time must be greater than the time before it");
    }
    if (path.keyframes.empty()) throw Error(prefix + "\"keyframes\" is empty");
    return path;
}

CameraPath loadCameraPath(const std::string& file) {
    std::string text;
    try {
        text = readTextFile(file);
    } catch (const Error& error) {
        throw Error(std::string("camera path ") + error.what());
    }
    return parseCameraPath(text, file);
}

std::string cameraPathToJson(const CameraPath& path) {
    json keyframes = json::array();
    for (const CameraKeyframe& key : path.keyframes) {
        const glm::quat& r = key.rotation;
        keyframes.push_back({{"time", key.time},
                             {"position", {key.wsPosition.x, key.wsPosition.y, key.wsPosition.z}},
                             {"rotation", {r.x, r.y, r.z, r.w}},
                             {"yfov", key.yfov}});
    }
    return json{{"keyframes", keyframes}}.dump(2) + "\n";
}

void saveCameraPath(const CameraPath& path, const std::string& file) { writeTextFile(file, cameraPathToJson(path)); }

CameraKeyframe keyframeOf(const Camera& camera, float time) {
    CameraKeyframe key;
    key.time = time;
    key.wsPosition = glm::vec3(camera.worldFromView[3]);
    key.rotation = glm::normalize(glm::quat_cast(glm::mat3(camera.worldFromView)));
    key.yfov = camera.yfov;
    return key;
}

Camera cameraOnPath(const CameraPath& path, float time, const Camera& base) {
    const std::vector<CameraKeyframe>& keys = path.keyframes;
    if (keys.empty()) return base;
    if (!(time > keys.front().time)) return cameraOf(keys.front(), base);
    if (time >= keys.back().time) return cameraOf(keys.back(), base);
    const auto next = std::upper_bound(keys.begin(), keys.end(), time,
                                       [](float t, const CameraKeyframe& key) { return t < key.time; });
    const CameraKeyframe& b = *next;
    const CameraKeyframe& a = *(next - 1);
    const float s = (time - a.time) / (b.time - a.time);
    CameraKeyframe key;
    key.wsPosition = glm::mix(a.wsPosition, b.wsPosition, s);
    key.rotation = glm::slerp(a.rotation, b.rotation, s);  // glm takes the short way round
    key.yfov = glm::mix(a.yfov, b.yfov, s);
    return cameraOf(key, base);
}

float scriptedPathTime(const CameraPath& path, uint32_t frame, uint32_t frames) {
    if (path.keyframes.empty()) return 0.0f;
    if (frames <= 1 || frame + 1 >= frames) return path.keyframes.back().time;
    return path.keyframes.front().time + path.duration() * float(frame) / float(frames - 1);
}

}  // namespace penumbra::viewer
