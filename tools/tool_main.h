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
    } catch (const CLI::CallForHelp& e) {
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

}  // namespace vr
