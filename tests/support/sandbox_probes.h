// Test support for the sandbox tests (test_child_process, test_grader_hostile):
// finding processes that outlived what started them, and a loopback TCP
// server that says whether anything reached it.
#pragma once

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cctype>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace voxlab::testing {

// Running (not zombie) processes, other than this one, whose command line
// holds `token`, anywhere on the machine.
inline int processesWith(const std::string& token) {
    int count = 0;
    for (const auto& entry : std::filesystem::directory_iterator("/proc")) {
        const std::string name = entry.path().filename().string();
        if (name.empty() || !std::isdigit(static_cast<unsigned char>(name[0])) || name == std::to_string(getpid()))
            continue;
        std::ifstream in(entry.path() / "cmdline", std::ios::binary);
        const std::string cmdline((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        std::ifstream stat(entry.path() / "stat");
        std::string line;
        std::getline(stat, line);
        const std::size_t close = line.rfind(')');
        const bool zombie = close != std::string::npos && line.size() > close + 2 && line[close + 2] == 'Z';
        if (cmdline.find(token) != std::string::npos && !zombie) ++count;
    }
    return count;
}

// A TCP server on 127.0.0.1 at a free port.
class LoopbackServer {
public:
    LoopbackServer() : fd_(socket(AF_INET, SOCK_STREAM, 0)) {
        sockaddr_in addr{};
        addr.sin_family = AF_INET;
        addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
        bound_ = bind(fd_, reinterpret_cast<sockaddr*>(&addr), sizeof addr) == 0;
        socklen_t len = sizeof addr;
        getsockname(fd_, reinterpret_cast<sockaddr*>(&addr), &len);
        port_ = ntohs(addr.sin_port);
        listen(fd_, 4);
    }
    ~LoopbackServer() { close(fd_); }
    LoopbackServer(const LoopbackServer&) = delete;
    LoopbackServer& operator=(const LoopbackServer&) = delete;

    bool bound() const { return bound_; }
    int port() const { return port_; }
    // Whether a connection that sent some bytes arrived within `ms`.
    bool received(int ms) {
        pollfd p = {fd_, POLLIN, 0};
        if (poll(&p, 1, ms) <= 0) return false;
        const int c = accept(fd_, nullptr, nullptr);
        char buf[16] = {};
        const bool got = read(c, buf, sizeof buf) > 0;
        close(c);
        return got;
    }

private:
    int fd_;
    bool bound_ = false;
    int port_ = 0;
};

}  // namespace voxlab::testing
