#include "support/cli.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "support/datasets.h"

extern char** environ;

namespace vr::test {
namespace fs = std::filesystem;

fs::path volprepExecutable() { return fs::path(VR_BINARY_DIR) / "preprocess" / "volprep"; }
fs::path volrenderExecutable() { return fs::path(VR_BINARY_DIR) / "volrender" / "volrender"; }
fs::path volphantomExecutable() { return fs::path(VR_BINARY_DIR) / "datasets" / "volphantom"; }

fs::path copiedWithoutModules(const fs::path& executable, const std::string& name) {
    const fs::path bin = scratchDir(name) / "bin";
    fs::create_directories(bin);
    fs::copy_file(executable, bin / executable.filename());
    return bin / executable.filename();
}

std::string shellQuote(const fs::path& p) {
    std::string out = "'";
    for (char c : p.string()) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

std::string slurp(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

CliOutcome runCli(const fs::path& executable, const std::string& args, const std::string& environment) {
    const fs::path dir = scratchDir("cli_streams_" + executable.filename().string() + "_" + std::to_string(::getpid()));
    const fs::path out = dir / "stdout.txt", err = dir / "stderr.txt";
    const std::string cmd = environment + (environment.empty() ? "" : " ") + shellQuote(executable) + " " + args +
                            " >" + shellQuote(out) + " 2>" + shellQuote(err);
    const int raw = std::system(cmd.c_str());
    return {WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, slurp(out), slurp(err)};
}

static CliOutcome runBuilt(const fs::path& executable, const std::string& args, const std::string& environment) {
    EXPECT_TRUE(fs::exists(executable)) << "build the " << executable.filename() << " target first: " << executable;
    return runCli(executable, args, environment);
}

CliOutcome runVolprep(const std::string& args, const std::string& environment) {
    return runBuilt(volprepExecutable(), args, environment);
}

CliOutcome runVolrender(const std::string& args, const std::string& environment) {
    return runBuilt(volrenderExecutable(), args, environment);
}

CliOutcome runOnTerminal(const fs::path& executable, const std::string& args) {
    EXPECT_TRUE(fs::exists(executable)) << "build the " << executable.filename() << " target first: " << executable;
    // script -e: its exit status is the command's; -q: nothing of its own on the terminal.
    return runCli("/usr/bin/script", "-qec " + shellQuote(shellQuote(executable) + " " + args) + " /dev/null");
}

void expectRefusal(const CliOutcome& r, const std::string& tool, const std::string& args,
                   const std::vector<std::string>& mentions) {
    EXPECT_NE(r.status, 0) << args;
    EXPECT_EQ(r.err.rfind(tool + ": ", 0), 0u) << args << "\n" << r.err;
    for (const std::string& m : mentions)
        EXPECT_NE(r.err.find(m), std::string::npos) << "expected '" << m << "' for " << args << " in:\n" << r.err;
}

bool killWhileWriting(const fs::path& executable, const std::vector<std::string>& args, const fs::path& folder,
                      const std::string& temporaryPrefix, double timeoutSeconds) {
    std::vector<std::string> argv{executable.string()};
    argv.insert(argv.end(), args.begin(), args.end());
    std::vector<char*> cargv;
    for (std::string& a : argv) cargv.push_back(a.data());
    cargv.push_back(nullptr);

    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
    pid_t pid = 0;
    const int spawned = posix_spawn(&pid, cargv[0], &actions, nullptr, cargv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (spawned != 0) return false;
    // The child at the lowest priority: on a machine busy with other tests, this poll must still run while the
    // child writes, or it sees the file only once renamed.
    ::setpriority(PRIO_PROCESS, id_t(pid), 19);

    const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeoutSeconds);
    bool killed = false;
    while (!killed && std::chrono::steady_clock::now() < deadline) {
        int status = 0;
        if (::waitpid(pid, &status, WNOHANG) == pid) return false;  // finished before we saw it write
        std::error_code ec;
        for (const auto& entry : fs::directory_iterator(folder, ec))
            if (entry.path().filename().string().rfind(temporaryPrefix, 0) == 0) {
                ::kill(pid, SIGKILL);
                killed = true;
                break;
            }
        if (!killed) ::usleep(200);
    }
    if (!killed) ::kill(pid, SIGKILL);
    int status = 0;
    ::waitpid(pid, &status, 0);
    return killed && WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL;
}

}  // namespace vr::test
