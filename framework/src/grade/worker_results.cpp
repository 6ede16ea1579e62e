// voxlab: the grade worker's results channel (see worker_results.h).
#include "voxlab/worker_results.h"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

#include "voxlab/error.h"
#include "voxlab/fd_io.h"
#include "voxlab/untrusted_text.h"

namespace voxlab {

using nlohmann::json;

namespace {

constexpr int kMaxSide = 8192;             // pixels; grading scenes are a few hundred
constexpr std::size_t kMaxHeader = 65536;  // bytes of one header line
constexpr std::size_t kMaxCheck = 16u << 20;
constexpr std::size_t kMaxStubs = 64;      // stubs a scene may name

bool inManifest(const StageManifest& m, const std::string& item, const std::string& name) {
    if (item == "stage") return name == "loop";  // the worker's runaway-loop check (an error record only)
    if (item == "scene")
        return std::any_of(m.scenes.begin(), m.scenes.end(), [&](const GradedScene& s) { return s.name == name; });
    return std::any_of(m.checks.begin(), m.checks.end(), [&](const GradedCheck& c) { return c.name == name; });
}

Image fromRgb8(int width, int height, const char* bytes) {
    Image img(width, height);
    for (std::size_t i = 0, n = std::size_t(width) * height; i < n; ++i) {
        for (int c = 0; c < 3; ++c) img.rgba[i * 4 + c] = static_cast<unsigned char>(bytes[i * 3 + c]) / 255.0f;
        img.rgba[i * 4 + 3] = 1.0f;
    }
    return img;
}

// Adds one record; throws Error for anything out of protocol.
std::size_t parseRecord(const std::string& stream, std::size_t at, const StageManifest& m, WorkerResults& r) {
    const std::size_t eol = stream.find('\n', at);
    if (eol == std::string::npos || eol - at > kMaxHeader) throw Error("a record header is cut short or too long");
    const json h = json::parse(stream.begin() + long(at), stream.begin() + long(eol));
    const std::string type = h.at("type").get<std::string>(), name = h.at("name").get<std::string>();
    const std::size_t bytes = h.at("bytes").get<std::size_t>();
    if (bytes > stream.size() - eol - 1) throw Error("record '" + name + "' is cut short");
    const char* payload = stream.data() + eol + 1;
    const std::string item = type == "error" ? h.at("item").get<std::string>() : type == "image" ? "scene" : "check";
    if ((type != "image" && type != "check" && type != "error") || !inManifest(m, item, name))
        throw Error("unexpected record " + type + " '" + name + "'");
    const std::string key = item + ":" + name;
    if (h.contains("stubs") && item == "scene") {
        const json& stubs = h.at("stubs");
        if (!stubs.is_array() || stubs.size() > kMaxStubs) throw Error("record '" + name + "': stubs is not a short list");
        for (const json& stub : stubs) r.stubs[name].push_back(safeText(stub.get<std::string>(), kMaxNameBytes));
    }
    if (r.errors.count(key) || (item == "scene" ? r.images.count(name) : r.checks.count(name)))
        throw Error("record " + key + " sent twice");
    if (type == "image") {
        const int w = h.at("width").get<int>(), hh = h.at("height").get<int>();
        if (w < 1 || hh < 1 || w > kMaxSide || hh > kMaxSide || bytes != std::size_t(w) * hh * 3)
            throw Error("image '" + name + "' has an impossible size");
        r.images.emplace(name, fromRgb8(w, hh, payload));
    } else if (type == "check") {
        if (bytes > kMaxCheck) throw Error("check '" + name + "' output is too large");
        r.checks.emplace(name, json::parse(payload, payload + bytes));
    } else {
        if (bytes != 0) throw Error("an error record carries no payload");
        // The worker's words, as data: a compile error's message is the whole log.
        r.errors[key] = {{"kind", safeText(h.at("kind").get<std::string>(), 64)},
                         {"message", safeText(h.at("message").get<std::string>(), kMaxLogBytes)}};
    }
    return eol + 1 + bytes;
}

}  // namespace

WorkerResults parseWorkerResults(const std::string& stream, const StageManifest& manifest) {
    WorkerResults r;
    for (std::size_t at = 0; at < stream.size();) {
        try {
            at = parseRecord(stream, at, manifest, r);
        } catch (const std::exception& e) {
            // A parser's message may quote the bytes it could not read.
            r.problem = safeText(std::string("the worker's results are malformed: ") + e.what());
            break;
        }
    }
    return r;
}

void WorkerResultWriter::record(const json& header, const std::string& payload) {
    // A message may quote the stage's own bytes (a compiler's log of an
    // #error line in Latin-1): invalid UTF-8 is sent as U+FFFD, not thrown on.
    const std::string text = header.dump(-1, ' ', false, json::error_handler_t::replace) + "\n" + payload;
    if (const int err = writeAll(fd_, text))
        throw Error(std::string("cannot send results to the grader (fd 3): ") + std::strerror(err));
}

void WorkerResultWriter::image(const std::string& scene, const Image& image, const std::vector<std::string>& stubs) {
    std::string rgb(std::size_t(image.width) * image.height * 3, '\0');
    for (std::size_t i = 0, n = std::size_t(image.width) * image.height; i < n; ++i)
        for (int c = 0; c < 3; ++c) rgb[i * 3 + c] = char(toByte(image.rgba[i * 4 + c]));
    json header = {{"type", "image"}, {"name", scene}, {"width", image.width}, {"height", image.height},
                   {"bytes", rgb.size()}};
    if (!stubs.empty()) header["stubs"] = stubs;
    record(header, rgb);
}

void WorkerResultWriter::check(const std::string& name, const json& result) {
    const std::string text = result.dump(-1, ' ', false, json::error_handler_t::replace);
    record({{"type", "check"}, {"name", name}, {"bytes", text.size()}}, text);
}

void WorkerResultWriter::error(const std::string& item, const std::string& name, const std::string& kind,
                               const std::string& message, const std::vector<std::string>& stubs) {
    json header = {{"type", "error"}, {"item", item}, {"name", name}, {"kind", kind}, {"message", message}, {"bytes", 0}};
    if (!stubs.empty()) header["stubs"] = stubs;
    record(header, "");
}

}  // namespace voxlab
