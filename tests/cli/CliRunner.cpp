#include "CliRunner.h"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <sys/wait.h>
#include <unistd.h>

namespace buoyancy_test {

namespace {
std::string slurp(const std::string& path) {
    std::ifstream f(path);
    std::stringstream s;
    s << f.rdbuf();
    return s.str();
}
}  // namespace

CliResult runCli(const std::vector<std::string>& args) {
    const std::string dir = scratchDir("cli_io");
    const std::string outPath = dir + "/out.txt", errPath = dir + "/err.txt";
    const pid_t pid = fork();
    if (pid < 0) throw std::runtime_error("fork failed");
    if (pid == 0) {
        if (!std::freopen(outPath.c_str(), "w", stdout) || !std::freopen(errPath.c_str(), "w", stderr)) _exit(127);
        std::vector<char*> argv;
        std::string exe = BUOYANCY_CLI_PATH;
        argv.push_back(exe.data());
        std::vector<std::string> copy = args;
        for (auto& a : copy) argv.push_back(a.data());
        argv.push_back(nullptr);
        execv(exe.c_str(), argv.data());
        _exit(127);
    }
    int status = 0;
    waitpid(pid, &status, 0);
    CliResult r;
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    r.out = slurp(outPath);
    r.err = slurp(errPath);
    return r;
}

std::string scratchDir(const std::string& name) {
    namespace fs = std::filesystem;
    const fs::path p = fs::temp_directory_path() / ("buoyancy_tests_" + std::to_string(getpid())) / name;
    fs::create_directories(p);
    return p.string();
}

void writeBoxObj(const std::string& path, double sx, double sy, double sz) {
    const double x = sx / 2, y = sy / 2, z = sz / 2;
    const double v[8][3] = {{-x, -y, -z}, {x, -y, -z}, {x, y, -z}, {-x, y, -z},
                            {-x, -y, z},  {x, -y, z},  {x, y, z},  {-x, y, z}};
    const int quads[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {2, 3, 7, 6}, {1, 2, 6, 5}, {0, 4, 7, 3}};
    std::ofstream f(path);
    f.precision(17);
    for (auto& p : v) f << "v " << p[0] << ' ' << p[1] << ' ' << p[2] << '\n';
    for (auto& q : quads) {
        f << "f " << q[0] + 1 << ' ' << q[1] + 1 << ' ' << q[2] + 1 << '\n';
        f << "f " << q[0] + 1 << ' ' << q[2] + 1 << ' ' << q[3] + 1 << '\n';
    }
}

}  // namespace buoyancy_test
