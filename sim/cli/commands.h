// The `zenith` command line, one file per subcommand: each registers its options on the
// application and returns what runs it once the command line is parsed.
#pragma once

#include <CLI/CLI.hpp>
#include <atomic>
#include <functional>
#include <string>

namespace zenith::cli {

struct Command {
    CLI::App* app = nullptr;  // the subcommand, to see whether it was chosen
    std::function<int()> run;
};

Command AddEphemerisCommand(CLI::App& app);  // ephemeris_command.cpp
Command AddRenderCommand(CLI::App& app);     // render_command.cpp
Command AddReplayCommand(CLI::App& app);     // replay_command.cpp
Command AddInfoCommand(CLI::App& app);       // info_command.cpp
Command AddLiveCommand(CLI::App& app);       // live_command.cpp

// Long runs (replay, live) stop after the frame in progress on Ctrl-C or a scheduler's SIGTERM:
// StopOnSignals installs the handlers and returns the flag the run polls; once it has stopped,
// StoppedExitCode is the shell's convention, 128 + the signal (130 for SIGINT, 143 for
// SIGTERM). stop_signal.cpp.
const std::atomic<bool>& StopOnSignals();
int StoppedExitCode();

// The command-line option of a library field named in an ArgumentError ("" if none).
std::string FlagForField(const std::string& field);

}  // namespace zenith::cli
