/// @file ChildProcessImport.cpp
/// fork() + pipe + poll() with a deadline. Wire format (native endianness, same binary on both ends):
///   u8 status (0 = mesh, 1 = error)
///   status 1: u64 length, message bytes (the MeshError text, already "FILE: problem")
///   status 0: u64 #warnings, then each as (u64 length, bytes);
///             u64 #V, 3·#V doubles; u64 #T, 3·#T int32; u64 #UV, 2·#UV doubles

#include "scene/ChildProcessImport.h"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <sstream>

#include <poll.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

namespace buoyancy::cli {

namespace {

ChildImportTestFault gTestFault = ChildImportTestFault::None;

// ---- child side ----
void appendBytes(std::string& buf, const void* p, std::size_t n) { buf.append(static_cast<const char*>(p), n); }
void appendU64(std::string& buf, std::uint64_t v) { appendBytes(buf, &v, sizeof v); }
void appendString(std::string& buf, const std::string& s) {
    appendU64(buf, s.size());
    buf += s;
}

bool writeAll(int fd, const char* data, std::size_t n) {
    while (n > 0) {
        const ssize_t w = ::write(fd, data, n);
        if (w < 0) {
            if (errno == EINTR) continue;
            return false;
        }
        data += w;
        n -= static_cast<std::size_t>(w);
    }
    return true;
}

[[noreturn]] void runChild(int fd, const std::string& path, double scale) {
    // A crash must end the child with its signal, not run handlers inherited from the parent
    // (test frameworks and crash reporters install some).
    for (int sig : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT}) std::signal(sig, SIG_DFL);
    if (gTestFault == ChildImportTestFault::Crash) std::raise(SIGSEGV);
    if (gTestFault == ChildImportTestFault::Hang)
        for (;;) ::pause();
    std::string buf;
    try {
        std::vector<MeshWarning> warnings;
        const TriangleMesh mesh = importMeshFile(path, scale, &warnings);
        std::uint8_t status = 0;
        appendBytes(buf, &status, 1);
        appendU64(buf, warnings.size());
        for (const MeshWarning& w : warnings) appendString(buf, w.message);
        appendU64(buf, mesh.vertices.size());
        for (const Eigen::Vector3d& v : mesh.vertices) appendBytes(buf, v.data(), 3 * sizeof(double));
        appendU64(buf, mesh.triangles.size());
        for (const Eigen::Vector3i& t : mesh.triangles) {
            const std::int32_t idx[3] = {t[0], t[1], t[2]};
            appendBytes(buf, idx, sizeof idx);
        }
        appendU64(buf, mesh.corner_uvs.size());
        for (const Eigen::Vector2d& t : mesh.corner_uvs) appendBytes(buf, t.data(), 2 * sizeof(double));
    } catch (const std::exception& e) {
        buf.clear();
        std::uint8_t status = 1;
        appendBytes(buf, &status, 1);
        appendString(buf, e.what());
    }
    const bool ok = writeAll(fd, buf.data(), buf.size());
    ::close(fd);
    ::_exit(ok ? 0 : 1);  // _exit: no atexit handlers or static destructors of the parent's copy
}

// ---- parent side ----
struct Reader {
    const std::string& buf;
    std::size_t pos = 0;
    bool take(void* out, std::size_t n) {
        if (buf.size() - pos < n) return false;
        std::memcpy(out, buf.data() + pos, n);
        pos += n;
        return true;
    }
    bool u64(std::uint64_t& v) { return take(&v, sizeof v); }
    bool count(std::uint64_t& n, std::size_t itemBytes) {  // a count whose items must fit in what is left
        return u64(n) && itemBytes > 0 && n <= (buf.size() - pos) / itemBytes;
    }
    bool str(std::string& s) {
        std::uint64_t n = 0;
        if (!count(n, 1)) return false;
        s.assign(buf.data() + pos, n);
        pos += n;
        return true;
    }
};

std::string secondsText(double s) {
    std::ostringstream o;
    o << s;
    return o.str();
}

}  // namespace

void setChildImportTestFaultForTesting(ChildImportTestFault fault) { gTestFault = fault; }

TriangleMesh importMeshInChildProcess(const std::string& path, double scale, double timeoutSeconds,
                                      std::vector<MeshWarning>* warnings) {
    const std::string name = std::filesystem::path(path).filename().string().empty()
                                 ? path
                                 : std::filesystem::path(path).filename().string();
    auto fail = [&](const std::string& problem) { return MeshError(name + ": " + problem); };
    if (!(timeoutSeconds > 0.0) || !std::isfinite(timeoutSeconds))
        throw fail("import time limit must be finite and > 0 (got " + secondsText(timeoutSeconds) + ")");

    int fds[2];
    if (::pipe(fds) != 0) throw fail(std::string("cannot create pipe: ") + std::strerror(errno));
    const pid_t pid = ::fork();
    if (pid < 0) {
        const int err = errno;
        ::close(fds[0]);
        ::close(fds[1]);
        throw fail(std::string("cannot fork the importer process: ") + std::strerror(err));
    }
    if (pid == 0) {
        ::close(fds[0]);
        runChild(fds[1], path, scale);
    }
    ::close(fds[1]);

    // Read everything the child writes until EOF or the deadline.
    using Clock = std::chrono::steady_clock;
    const auto deadline = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                             std::chrono::duration<double>(timeoutSeconds));
    std::string data;
    char chunk[1 << 16];
    bool timedOut = false;
    bool readError = false;
    for (;;) {
        const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
        if (left <= 0) { timedOut = true; break; }
        pollfd p{fds[0], POLLIN, 0};
        const int r = ::poll(&p, 1, static_cast<int>(std::min<long long>(left + 1, 1000)));
        if (r < 0) {
            if (errno == EINTR) continue;
            readError = true;
            break;
        }
        if (r == 0) continue;  // re-check the deadline
        const ssize_t n = ::read(fds[0], chunk, sizeof chunk);
        if (n < 0) {
            if (errno == EINTR || errno == EAGAIN) continue;
            readError = true;
            break;
        }
        if (n == 0) break;  // EOF: the child closed its end (finished or died)
        data.append(chunk, static_cast<std::size_t>(n));
    }
    ::close(fds[0]);
    if (timedOut) ::kill(pid, SIGKILL);

    int status = 0;
    while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    if (timedOut) throw fail("import timed out after " + secondsText(timeoutSeconds) + " s");
    if (WIFSIGNALED(status))
        throw fail("importer crashed (signal " + std::to_string(WTERMSIG(status)) + ")");
    if (readError) throw fail("cannot read from the importer process");
    if (WIFEXITED(status) && WEXITSTATUS(status) != 0 && data.empty())
        throw fail("importer process failed (exit code " + std::to_string(WEXITSTATUS(status)) + ")");

    Reader in{data};
    std::uint8_t kind = 255;
    const std::string truncated = "importer process sent a truncated or malformed result";
    if (!in.take(&kind, 1)) throw fail(truncated);
    if (kind == 1) {
        std::string message;
        if (!in.str(message)) throw fail(truncated);
        throw MeshError(message);  // already "FILE: problem"
    }
    if (kind != 0) throw fail(truncated);
    TriangleMesh mesh;
    std::uint64_t n = 0;
    if (!in.count(n, 8)) throw fail(truncated);
    for (std::uint64_t i = 0; i < n; ++i) {
        std::string w;
        if (!in.str(w)) throw fail(truncated);
        if (warnings != nullptr) warnings->push_back({w});
    }
    if (!in.count(n, 3 * sizeof(double))) throw fail(truncated);
    mesh.vertices.resize(n);
    for (Eigen::Vector3d& v : mesh.vertices) in.take(v.data(), 3 * sizeof(double));
    if (!in.count(n, 3 * sizeof(std::int32_t))) throw fail(truncated);
    mesh.triangles.resize(n);
    for (Eigen::Vector3i& t : mesh.triangles) {
        std::int32_t idx[3] = {0, 0, 0};
        in.take(idx, sizeof idx);
        t = Eigen::Vector3i(idx[0], idx[1], idx[2]);
    }
    if (!in.count(n, 2 * sizeof(double))) throw fail(truncated);
    mesh.corner_uvs.resize(n);
    for (Eigen::Vector2d& t : mesh.corner_uvs) in.take(t.data(), 2 * sizeof(double));
    if (in.pos != data.size()) throw fail(truncated);
    return mesh;
}

}  // namespace buoyancy::cli
