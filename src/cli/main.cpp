// sphclip: scene file -> SPH simulation -> per-frame outputs, on a machine
// with no screen. See README.md for the command line and exit codes.

#include "cli/compare_command.hpp"
#include "cli/console.hpp"
#include "cli/exit_codes.hpp"
#include "cli/stop_signals.hpp"
#include "cli/run_command.hpp"
#include "cli/study_command.hpp"
#include "cli/validate_command.hpp"
#include "io/input_error.hpp"
#include "render/gl_context.hpp"

#include <CLI/CLI.hpp>
#include <exception>
#include <fmt/format.h>
#include <string>

namespace {

std::string join_arguments(int argc, char** argv) {
    std::string line;
    for (int i = 0; i < argc; ++i)
        line += (i ? " " : "") + std::string(argv[i]);
    return line;
}

void print_keys(bool markdown) {
    const auto keys = sph::scene_keys();
    if (markdown) {
        fmt::print("| key | type | unit | default | meaning |\n|---|---|---|---|---|\n");
        for (const auto& k : keys)
            fmt::print("| `{}` | {} | {} | {} | {} |\n", k.path, k.type, k.unit, k.default_value,
                       k.description);
        fmt::print("\nA vector has one number per dimension (2 or 3).\n");
        return;
    }
    for (const auto& k : keys)
        fmt::print("{:<26} {:<8} default {:<30} {}\n", k.path, k.unit.empty() ? "-" : k.unit,
                   k.default_value.empty() ? "-" : k.default_value, k.description);
}

} // namespace

int main(int argc, char** argv) {
    // Before anything else: a stop asked for during start-up is kept, and
    // the run it reaches ends as interrupted (exit 130).
    const sph::StopSignals stop_signals;
    CLI::App app{
        "sphclip: turns a scene file into a fluid clip (SPH) on a machine with no screen."};
    app.set_version_flag("--version", SPHCLIP_VERSION);
    app.require_subcommand(1);

    sph::RunCommandLine run;
    sph::add_run_command(app, run);

    bool markdown = false;
    auto* keys_cmd =
        app.add_subcommand("keys", "List every scene key with unit, default, meaning.");
    keys_cmd->add_flag("--markdown", markdown, "As a Markdown table");

    sph::CompareCliOptions compare;
    auto* compare_cmd = sph::add_compare_command(app, compare);

    sph::ValidateOptions validate;
    auto* validate_cmd = sph::add_validate_command(app, validate);

    sph::StudyOptions study;
    auto* study_cmd = sph::add_study_command(app, study);

    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        const int code = app.exit(e);
        return code == 0 ? sph::exit_success : sph::exit_bad_input;
    }

    try {
        if (*keys_cmd) {
            print_keys(markdown);
            return sph::exit_success;
        }
        if (*compare_cmd)
            return sph::compare_command(compare);
        if (*validate_cmd)
            return sph::validate_command(validate);
        if (*study_cmd) {
            study.command_line = join_arguments(argc, argv);
            return sph::study_command(study);
        }
        return sph::run_command(sph::run_options(run, join_arguments(argc, argv)));
    } catch (const sph::GlContextError& e) {
        sph::say(stderr, "sphclip: error: {}\nsphclip: (--no-png --no-mp4 runs need no OpenGL)\n",
                   e.what());
        return sph::exit_no_gl_context;
    } catch (const sph::InputError& e) {
        sph::say(stderr, "sphclip: error: {}\n", e.what());
        return sph::exit_bad_input;
    } catch (const std::exception& e) {
        sph::say(stderr, "sphclip: error: {}\n", e.what());
        return sph::exit_failure;
    }
}
