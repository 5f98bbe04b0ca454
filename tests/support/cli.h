// Running the built command-line tools from tests: their paths, a shell run capturing both streams, and a run
// killed while it writes its output.
#pragma once
#include <filesystem>
#include <string>
#include <vector>

namespace vr::test {

std::filesystem::path volprepExecutable();
std::filesystem::path volrenderExecutable();
std::filesystem::path volphantomExecutable();

// A copy of `executable` in bin/ of a fresh scratch folder `name` (scratchDir), which holds no lib/volrender/: the
// tool without its modules (tools/runtime_module.h). Returns the copy.
std::filesystem::path copiedWithoutModules(const std::filesystem::path& executable, const std::string& name);

// A path single-quoted for the shell.
std::string shellQuote(const std::filesystem::path& p);
std::string slurp(const std::filesystem::path& p);

struct CliOutcome {
    int status;  // exit status; -1 when killed by a signal
    std::string out, err;
};

// Runs `environment executable args` through the shell (args quoted by the caller), capturing stdout and stderr.
CliOutcome runCli(const std::filesystem::path& executable, const std::string& args,
                  const std::string& environment = "");

// runCli on the built volprep / volrender, failing the test (non-fatally) when that executable is not built.
CliOutcome runVolprep(const std::string& args, const std::string& environment = "");
CliOutcome runVolrender(const std::string& args, const std::string& environment = "");
// What `executable args` writes to a terminal (a pseudo-terminal from util-linux's script(1), stdout and stderr
// together), as a user at a console sees it; its exit status.
CliOutcome runOnTerminal(const std::filesystem::path& executable, const std::string& args);

// A refusal by `tool` of `args`: a non-zero exit status, stderr starting with "TOOL: " and naming each of `mentions`.
void expectRefusal(const CliOutcome& r, const std::string& tool, const std::string& args,
                   const std::vector<std::string>& mentions);

// Starts executable with args (no shell, output discarded) and SIGKILLs it as soon as a file whose name starts with
// `temporaryPrefix` appears in `folder`. Returns whether it was killed while that file existed (false: the run
// ended, or timeoutSeconds passed, before it was seen).
bool killWhileWriting(const std::filesystem::path& executable, const std::vector<std::string>& args,
                      const std::filesystem::path& folder, const std::string& temporaryPrefix, double timeoutSeconds);

}  // namespace vr::test
