// tidepool: expand, validate, render and report GLSL ES water shader variants.
//
// This front end runs the commands that need no GL itself and hands the ones that render
// (kGlCommands) to `tidepool-gl`, next to it, with the same arguments: loading Mesa, LLVM, z3
// and ICU costs about 40 MB and 20 shared libraries at start-up, which `validate` and `expand`
// should not pay.
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <initializer_list>
#include <string>
#include <string_view>

#include "CliSupport.h"
#include "Commands.h"
#include <unistd.h>

namespace {

// The subcommand is the first argument that is not an option: the top level has only flags.
bool NamesGlCommand(int argc, char** argv) {
    for (int i = 1; i < argc; ++i) {
        const std::string_view arg = argv[i];
        if (!arg.empty() && arg[0] == '-') {
            continue;
        }
        for (const tidepool::cli::GlCommand& command : tidepool::cli::kGlCommands) {
            if (arg == command.name) {
                return true;
            }
        }
        return false;
    }
    return false;
}

// Replaces this process with tidepool-gl from this executable's folder; returns only when that
// fails, with the exit code of an environment error (message printed).
int ExecGlCommands(char** argv) {
    std::error_code ec;
    const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
    const std::filesystem::path gl =
            (ec ? std::filesystem::path(argv[0]) : self).parent_path() / "tidepool-gl";
    // argv[0] stays as the user typed it, so help and errors still name `tidepool`.
    ::execv(gl.c_str(), argv);
    std::fprintf(stderr,
                 "error: cannot run %s: %s; the commands that render (render, bench, run, "
                 "stability, plan) live in tidepool-gl, which must be next to tidepool\n",
                 gl.c_str(), std::strerror(errno));
    return tidepool::cli::kExitEnvironment;
}

// The GL commands in --help: their names and summaries only (tidepool-gl parses their flags).
void ListGlCommands(CLI::App& app, std::initializer_list<std::string_view> names) {
    for (std::string_view name : names) {
        app.add_subcommand(std::string(name), tidepool::cli::GlCommandSummary(name));
    }
}

}  // namespace

int main(int argc, char** argv) {
    if (NamesGlCommand(argc, argv)) {
        return ExecGlCommands(argv);
    }
    CLI::App app{tidepool::cli::kAppDescription};
    int exit_code = tidepool::cli::kExitOk;
    // The order of the help list is the order tidepool-gl registers the commands in.
    tidepool::cli::RegisterExpandCommand(app, exit_code);
    tidepool::cli::RegisterValidateCommand(app, exit_code);
    tidepool::cli::RegisterStatsCommand(app, exit_code);
    ListGlCommands(app, {"render", "bench"});
    tidepool::cli::RegisterReportCommand(app, exit_code);
    ListGlCommands(app, {"run", "stability", "plan"});
    return tidepool::cli::ParseAndRun(app, argc, argv, exit_code);
}
