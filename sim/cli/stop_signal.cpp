#include <atomic>
#include <csignal>

#include "commands.h"

namespace zenith::cli {
namespace {

std::atomic<bool> g_stop{false};
std::atomic<int> g_signal{0};

extern "C" void OnStopSignal(int signal) {
    g_signal.store(signal);
    g_stop.store(true);
}

}  // namespace

const std::atomic<bool>& StopOnSignals() {
    std::signal(SIGINT, OnStopSignal);
    std::signal(SIGTERM, OnStopSignal);
    return g_stop;
}

int StoppedExitCode() { return 128 + (g_signal.load() != 0 ? g_signal.load() : SIGINT); }

}  // namespace zenith::cli
