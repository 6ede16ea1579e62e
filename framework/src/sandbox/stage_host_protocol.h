// voxlab grader internals: the stage host's wire protocol (stage_host.h
// describes it), shared by the worker's side (stage_host.cpp) and the host
// program (framework/stage_host/stage_host_main.cpp).
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <tuple>
#include <type_traits>
#include <vector>

#include <glm/glm.hpp>

#include "voxlab/fd_io.h"
#include "voxlab/stage_library.h"

namespace voxlab::stage_host {

constexpr std::uint32_t kMaxPoints = 64;      // values of a vector result (a plane meets a box in at most 6)
constexpr std::uint32_t kMaxMessage = 4096;
constexpr std::uint32_t kMaxBatch = 1u << 14;  // calls in one batch
// The host reads calls on stdin and answers on fd 3, so that what the
// stage prints (stdout, stderr) goes to the worker's log, not into answers.
constexpr int kAnswers = 3;

// Writes `size` bytes from `data` whole (fd_io.h).
inline bool sendAll(int fd, const void* data, std::size_t size) {
    return writeAll(fd, std::string_view(static_cast<const char*>(data), size)) == 0;
}

// A call is its function's op (its index in VOXLAB_CPP_STAGE_FUNCTIONS)
// and its arguments; the answer is a status byte ('O', or 'N' / 'E' and a
// message) and, after 'O', the result. Both ends are built together by the
// same compiler, so values cross as their bytes:
//  - an argument or a result that is trivially copyable (a number, a glm
//    vector, a Camera, a ShearWarp, ...) as the bytes of its value;
//  - a pointer argument as the kPointedValues values it points to (the
//    contracts' only one is cubeCase's corners);
//  - a vector result as a uint32 count, at most kMaxPoints, and its elements.
// A batch (stage_library.h's StageBatch) is kBatch, the function's op, a
// uint32 count <= kMaxBatch and each call's arguments as above; its answer
// is 'O' and the count's results one after another, or the first failing
// call's 'N' / 'E'. The worker reads the host's answers as untrusted: a
// count past the limit ends the host.
enum Op : unsigned char {
#define VOXLAB_STAGE_OP(name, Result, Parameters) kOp_##name,
    VOXLAB_CPP_STAGE_FUNCTIONS(VOXLAB_STAGE_OP)
#undef VOXLAB_STAGE_OP
    kOpCount
};
constexpr unsigned char kBatch = 0xFF;  // then the function's op
static_assert(kOpCount < kBatch, "too many C++ stage functions for the op byte");
constexpr std::size_t kPointedValues = 8;

template <class T>
struct Arg {  // by value or by const reference
    using Value = std::decay_t<T>;
    static_assert(std::is_trivially_copyable_v<Value>, "a stage function's argument must be trivially copyable");
    static constexpr std::size_t kWireSize = sizeof(Value);
    Value value{};
    static void put(std::string& out, const Value& v) { out.append(reinterpret_cast<const char*>(&v), sizeof v); }
    void load(const char* wire) { std::memcpy(&value, wire, sizeof value); }
    const Value& get() const { return value; }
};

template <class T>
struct Arg<const T*> {
    static_assert(std::is_trivially_copyable_v<T>);
    static constexpr std::size_t kWireSize = sizeof(T) * kPointedValues;
    T values[kPointedValues]{};
    static void put(std::string& out, const T* p) { out.append(reinterpret_cast<const char*>(p), sizeof values); }
    void load(const char* wire) { std::memcpy(values, wire, sizeof values); }
    const T* get() const { return values; }
};

template <class R>
struct Answer {
    static_assert(std::is_trivially_copyable_v<R>, "a stage function's result must be trivially copyable or a vector");
    static void put(std::string& out, const R& r) { out.append(reinterpret_cast<const char*>(&r), sizeof r); }
    static bool read(int fd, R* r) { return readAll(fd, r, sizeof *r); }
    static bool readMany(int fd, R* r, std::size_t count) { return readAll(fd, r, count * sizeof *r); }
    static std::string tooLarge(const R&) { return ""; }
};

template <class T>
struct Answer<std::vector<T>> {
    static_assert(std::is_trivially_copyable_v<T>);
    // Why the host refuses to send `r` (too many values), or "".
    static std::string tooLarge(const std::vector<T>& r) {
        return r.size() > kMaxPoints ? std::to_string(r.size()) + " values (at most " + std::to_string(kMaxPoints) + ")"
                                     : "";
    }
    static void put(std::string& out, const std::vector<T>& r) {
        const std::uint32_t count = std::uint32_t(r.size());
        out.append(reinterpret_cast<const char*>(&count), 4);
        out.append(reinterpret_cast<const char*>(r.data()), count * sizeof(T));
    }
    static bool read(int fd, std::vector<T>* r) {
        std::uint32_t count = 0;
        if (!readAll(fd, &count, 4) || count > kMaxPoints) return false;
        r->resize(count);
        return readAll(fd, r->data(), count * sizeof(T));
    }
    static bool readMany(int fd, std::vector<T>* r, std::size_t count) {
        for (std::size_t i = 0; i < count; ++i)
            if (!read(fd, r + i)) return false;
        return true;
    }
};

// One call's arguments as the host holds them, read from the wire.
template <class... A>
struct Call {
    static constexpr std::size_t kWireSize = (Arg<A>::kWireSize + ... + 0);
    std::tuple<Arg<A>...> args;
    void load(const char* wire) {
        std::apply([&](auto&... arg) { ((arg.load(wire), wire += std::decay_t<decltype(arg)>::kWireSize), ...); },
                   args);
    }
    bool read(int fd) {
        char wire[kWireSize + 1];
        if (!readAll(fd, wire, kWireSize)) return false;
        load(wire);
        return true;
    }
    template <class R>
    R apply(R (*f)(A...)) const {
        return std::apply([&](const auto&... arg) { return f(arg.get()...); }, args);
    }
};

}  // namespace voxlab::stage_host
