// What every command-line tool shares: parse the flags with CLI11, run, and turn a failure into one line on
// stderr ("TOOL: message") and an exit status: 2 for a bad command line, 1 for bad input or a failed run.
#pragma once
#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <functional>

namespace vr {

inline int runTool(const char* tool, CLI::App& app, int argc, char** argv, const std::function<int()>& run) {
    try {
        app.parse(argc, argv);
    } catch (const CLI::Success& e) {  // --help, or a flag that printed a listing: nothing to run
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        std::fprintf(stderr, "%s: %s\nRun %s --help for the options.\n", tool, e.what(), tool);
        return 2;
    }
    try {
        return run();
    } catch (const std::exception& e) {  // InputError names the file and the problem; others say what failed
        std::fprintf(stderr, "%s: %s\n", tool, e.what());
    }
    return 1;
}

// What --help says of a tool: its name, what it does and its exit statuses.
struct ToolText {
    const char* name;
    const char* description;
    const char* exitStatus;
};

// runTool over the flags that addFlags declares, which `run` receives once parsed.
template <typename Flags>
int runTool(const ToolText& text, int argc, char** argv, void (*addFlags)(CLI::App&, Flags&),
            const std::function<int(const Flags&)>& run) {
    CLI::App app{text.description};
    app.footer(text.exitStatus);
    Flags flags;
    addFlags(app, flags);
    return runTool(text.name, app, argc, argv, [&] { return run(flags); });
}

}  // namespace vr
