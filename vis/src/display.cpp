#include "display.h"

#include <dlfcn.h>
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string_view>
#include <thread>

namespace zenith::vis {
namespace {

constexpr const char* kInstallHint =
    "zenith-plot draws with VTK, and Debian's VTK 9 needs an X display (it is built for X11 "
    "only). Either run it on a desktop, set DISPLAY to a display you can open, run it under "
    "`xvfb-run -a zenith-plot ...`, or install Xvfb so that zenith-plot can start its own: "
    "`apt-get install xvfb xauth`.";

// Xlib through dlopen: Display* is opaque here.
struct XLib {
    void* handle = nullptr;
    void* (*open_display)(const char*) = nullptr;
    int (*close_display)(void*) = nullptr;
    std::string error;

    XLib() {
        handle = dlopen("libX11.so.6", RTLD_NOW | RTLD_LOCAL);
        if (handle == nullptr) {
            const char* e = dlerror();
            error =
                std::string("cannot load libX11.so.6 (") + (e ? e : "?") + "); install libx11-6";
            return;
        }
        open_display = reinterpret_cast<void* (*)(const char*)>(dlsym(handle, "XOpenDisplay"));
        close_display = reinterpret_cast<int (*)(void*)>(dlsym(handle, "XCloseDisplay"));
        if (open_display == nullptr || close_display == nullptr) {
            error = "libX11.so.6 lacks XOpenDisplay/XCloseDisplay";
        }
    }
    // Not closed: VTK links libX11 itself, and unloading it under Xlib's feet helps nobody.
};

XLib& X() {
    static XLib x;
    return x;
}

std::string FindOnPath(std::string_view program) {
    const char* path = std::getenv("PATH");
    if (path == nullptr) return {};
    std::string_view rest(path);
    while (true) {
        const std::size_t colon = rest.find(':');
        const std::string_view dir = rest.substr(0, colon);
        if (!dir.empty()) {
            const std::filesystem::path candidate = std::filesystem::path(dir) / program;
            if (access(candidate.c_str(), X_OK) == 0) return candidate.string();
        }
        if (colon == std::string_view::npos) break;
        rest.remove_prefix(colon + 1);
    }
    return {};
}

// Starts `xvfb -displayfd W -nolisten tcp -screen 0 1600x1200x24` and returns its pid and the
// display number it chose (it picks a free one itself, so parallel runs do not collide).
pid_t StartXvfb(const std::string& xvfb, std::string* display) {
    int fds[2];
    if (pipe(fds) != 0) throw DisplayError(std::string("pipe: ") + std::strerror(errno));
    const pid_t pid = fork();
    if (pid < 0) throw DisplayError(std::string("fork: ") + std::strerror(errno));
    if (pid == 0) {
        close(fds[0]);
        const int null_fd = open("/dev/null", O_RDWR);
        if (null_fd >= 0) {
            dup2(null_fd, STDIN_FILENO);
            dup2(null_fd, STDOUT_FILENO);
            dup2(null_fd, STDERR_FILENO);
        }
        const std::string fd_text = std::to_string(fds[1]);
        execl(xvfb.c_str(), xvfb.c_str(), "-displayfd", fd_text.c_str(), "-nolisten", "tcp",
              "-screen", "0", "1600x1200x24", static_cast<char*>(nullptr));
        _exit(127);
    }
    close(fds[1]);
    std::string number;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
    while (std::chrono::steady_clock::now() < deadline) {
        pollfd p{fds[0], POLLIN, 0};
        if (poll(&p, 1, 200) > 0) {
            char buffer[32];
            const ssize_t n = read(fds[0], buffer, sizeof buffer);
            if (n <= 0) break;  // Xvfb exited
            number.append(buffer, static_cast<std::size_t>(n));
            if (number.find('\n') != std::string::npos) break;
        }
    }
    close(fds[0]);
    while (!number.empty() && (number.back() == '\n' || number.back() == ' ')) number.pop_back();
    if (number.empty()) {
        kill(pid, SIGTERM);
        int status = 0;
        waitpid(pid, &status, 0);
        throw DisplayError("started " + xvfb + " but it reported no display number within 20 s. " +
                           kInstallHint);
    }
    *display = ":" + number;
    return pid;
}

}  // namespace

bool CanOpenDisplay(const char* name, std::string* why) {
    XLib& x = X();
    if (!x.error.empty()) {
        if (why != nullptr) *why = x.error;
        return false;
    }
    void* display = x.open_display(name);
    if (display == nullptr) {
        if (why != nullptr) {
            const char* shown = name != nullptr ? name : std::getenv("DISPLAY");
            *why = std::string("cannot open X display '") + (shown ? shown : "") + "'";
        }
        return false;
    }
    x.close_display(display);
    return true;
}

DisplayGuard::~DisplayGuard() {
    if (xvfb_pid_ > 0) {
        kill(xvfb_pid_, SIGTERM);
        int status = 0;
        waitpid(xvfb_pid_, &status, 0);
        if (had_display_) {
            setenv("DISPLAY", previous_display_.c_str(), 1);
        } else {
            unsetenv("DISPLAY");
        }
    }
}

DisplayGuard::DisplayGuard(DisplayGuard&& other) noexcept
    : display_(std::move(other.display_)),
      xvfb_pid_(other.xvfb_pid_),
      had_display_(other.had_display_),
      previous_display_(std::move(other.previous_display_)) {
    other.xvfb_pid_ = -1;
}

DisplayGuard EnsureDisplay(bool verbose) {
    DisplayGuard guard;
    const char* current = std::getenv("DISPLAY");
    guard.had_display_ = current != nullptr;
    if (current != nullptr) guard.previous_display_ = current;

    std::string why;
    if (current != nullptr && *current != '\0') {
        if (CanOpenDisplay(current, &why)) {
            guard.display_ = current;
            return guard;
        }
    } else {
        why = "DISPLAY is not set";
    }
    if (!X().error.empty()) throw DisplayError(X().error + ". " + kInstallHint);

    const std::string xvfb = FindOnPath("Xvfb");
    if (xvfb.empty()) {
        throw DisplayError("no X display (" + why + ") and no Xvfb on PATH. " + kInstallHint);
    }
    std::string display;
    const pid_t pid = StartXvfb(xvfb, &display);
    guard.xvfb_pid_ = pid;  // from here on the guard stops it, whatever happens
    guard.display_ = display;
    setenv("DISPLAY", display.c_str(), 1);
    // -displayfd reports when the server listens; still, give it a moment if the first open
    // races with its start-up.
    for (int attempt = 0; attempt < 50; ++attempt) {
        if (CanOpenDisplay(display.c_str(), &why)) {
            if (verbose) {
                std::fprintf(stderr, "zenith-plot: started %s on %s\n", xvfb.c_str(),
                             display.c_str());
            }
            return guard;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    throw DisplayError("started " + xvfb + " on " + display + " but " + why + ". " + kInstallHint);
}

}  // namespace zenith::vis
