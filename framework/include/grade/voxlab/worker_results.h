// voxlab: what a grade worker sends back to the grader.
//
// A worker (`voxlab grade-worker`) runs one stage of one implementation in
// a sandbox that can write no file the grader reads. It sends its results
// through the results channel (file descriptor 3, child_process.h), as a
// sequence of records, each a one-line JSON header and `bytes` raw bytes:
//
//   {"type":"image","name":SCENE,"width":W,"height":H,"bytes":W*H*3}\n RGB8 rows, top first
//   {"type":"check","name":CHECK,"bytes":N}\n  the check's JSON output
//   {"type":"error","item":"scene"|"check","name":NAME,"kind":K,"message":M,"bytes":0}\n
//
// An image or a scene's error may carry "stubs": the starter code's stubs
// the scene reached, each "stage/function" (grading.h's stubsReached: the
// checkerboard showed, or a C++ stage's function threw NotImplemented).
//
// kind is "compile_error", "not_implemented" or "error". The grader parses
// the stream with parseWorkerResults(), which accepts only names of the
// stage's manifest, each once, with sizes that add up; anything else is a
// protocol error and earns nothing. A worker cannot reach the expected
// outputs, so what it sends is only ever its own rendering.
#pragma once

#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "voxlab/grading.h"
#include "voxlab/image.h"

namespace voxlab {

// The worker's side: writes records to a file descriptor, every write checked.
class WorkerResultWriter {
public:
    explicit WorkerResultWriter(int fd) : fd_(fd) {}
    void image(const std::string& scene, const Image& image, const std::vector<std::string>& stubs = {});
    void check(const std::string& name, const nlohmann::json& result);
    void error(const std::string& item, const std::string& name, const std::string& kind, const std::string& message,
               const std::vector<std::string>& stubs = {});

private:
    void record(const nlohmann::json& header, const std::string& payload);
    int fd_;
};

struct WorkerResults {
    std::map<std::string, Image> images;           // scene -> image (as read back from 8 bits)
    std::map<std::string, nlohmann::json> checks;  // check -> its output
    std::map<std::string, nlohmann::json> errors;  // "scene:NAME" / "check:NAME" -> {"kind", "message"}
    std::map<std::string, std::vector<std::string>> stubs;  // scene -> the stubs it reached ("stage/function")
    std::string problem;                           // why the stream was cut short, if it was
};

// Parses a worker's stream against the stage's manifest (see above).
WorkerResults parseWorkerResults(const std::string& stream, const StageManifest& manifest);

}  // namespace voxlab
