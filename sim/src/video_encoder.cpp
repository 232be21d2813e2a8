#include "video_encoder.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <vector>

extern char** environ;

namespace zenith::sim {
namespace {

constexpr std::size_t kStderrTail = 4096;

std::string Errno(int error) { return std::strerror(error); }

// Writes all bytes to a pipe without letting a reader that went away kill the process: SIGPIPE
// is blocked for this thread during the write (EPIPE is returned instead) and any SIGPIPE it
// raised is consumed before the mask is restored.
bool WriteAll(int fd, const char* data, std::size_t size) {
    sigset_t pipe_set, old_set;
    sigemptyset(&pipe_set);
    sigaddset(&pipe_set, SIGPIPE);
    pthread_sigmask(SIG_BLOCK, &pipe_set, &old_set);
    bool ok = true;
    while (size > 0) {
        const ssize_t n = ::write(fd, data, size);
        if (n < 0) {
            if (errno == EINTR) continue;
            ok = false;
            break;
        }
        data += n;
        size -= static_cast<std::size_t>(n);
    }
    const timespec zero{0, 0};
    while (sigtimedwait(&pipe_set, nullptr, &zero) > 0) {
    }
    pthread_sigmask(SIG_SETMASK, &old_set, nullptr);
    return ok;
}

}  // namespace

VideoEncoder::VideoEncoder(const std::filesystem::path& output, double fps)
    : output_(std::filesystem::absolute(output)) {
    Require<VideoError>("fps", fps, "", Range::LeftOpen(0.0, 1000.0));
    partial_ = output_;
    partial_ += ".partial.mp4";
    int in_pipe[2], err_pipe[2];
    if (::pipe2(in_pipe, O_CLOEXEC) != 0) Fail("cannot make a pipe: " + Errno(errno));
    if (::pipe2(err_pipe, O_CLOEXEC) != 0) {
        ::close(in_pipe[0]);
        ::close(in_pipe[1]);
        Fail("cannot make a pipe: " + Errno(errno));
    }
    // The output as a file: URL, so that ffmpeg reads no option, protocol or pattern in it.
    const std::string target = "file:" + partial_.string();
    const std::string rate = fmt::format("{}", fps);
    std::vector<std::string> args = {
        "ffmpeg",     "-hide_banner", "-loglevel", "error",   "-y",
        "-f",         "image2pipe",   "-c:v",      "png",     "-framerate",
        rate,         "-i",           "pipe:0",    "-vf",     "pad=ceil(iw/2)*2:ceil(ih/2)*2",
        "-c:v",       "libx264",      "-pix_fmt",  "yuv420p", "-movflags",
        "+faststart", "-f",           "mp4",       target};
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);

    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_adddup2(&actions, in_pipe[0], STDIN_FILENO);
    posix_spawn_file_actions_adddup2(&actions, err_pipe[1], STDERR_FILENO);
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
    const int spawned = posix_spawnp(&pid_, "ffmpeg", &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    ::close(in_pipe[0]);
    ::close(err_pipe[1]);
    if (spawned != 0) {
        ::close(in_pipe[1]);
        ::close(err_pipe[0]);
        pid_ = -1;
        Fail(spawned == ENOENT ? std::string("ffmpeg is not installed (apt-get install ffmpeg)")
                               : "cannot start ffmpeg: " + Errno(spawned));
    }
    stdin_fd_ = in_pipe[1];
    stderr_fd_ = err_pipe[0];
    stderr_reader_ = std::thread([this] {
        std::array<char, 4096> buffer;
        for (;;) {
            const ssize_t n = ::read(stderr_fd_, buffer.data(), buffer.size());
            if (n < 0 && errno == EINTR) continue;
            if (n <= 0) break;
            stderr_tail_.append(buffer.data(), static_cast<std::size_t>(n));
            if (stderr_tail_.size() > 2 * kStderrTail) {
                stderr_tail_.erase(0, stderr_tail_.size() - kStderrTail);
            }
        }
    });
}

VideoEncoder::~VideoEncoder() {
    if (stdin_fd_ >= 0) ::close(stdin_fd_);
    if (pid_ > 0) {
        if (!finished_) ::kill(pid_, SIGTERM);
        Wait();
    }
    if (stderr_reader_.joinable()) stderr_reader_.join();
    if (stderr_fd_ >= 0) ::close(stderr_fd_);
    if (!finished_) {
        std::error_code ignored;
        std::filesystem::remove(partial_, ignored);
    }
}

int VideoEncoder::Wait() {
    int status = 0;
    while (::waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
    }
    pid_ = -1;
    return status;
}

void VideoEncoder::Fail(const std::string& what) {
    std::string message = "video '" + output_.string() + "' not encoded: " + what;
    if (stderr_reader_.joinable()) {
        if (stdin_fd_ >= 0) {
            ::close(stdin_fd_);
            stdin_fd_ = -1;
        }
        if (pid_ > 0) Wait();
        stderr_reader_.join();
    }
    std::string tail = stderr_tail_;
    if (tail.size() > kStderrTail) tail.erase(0, tail.size() - kStderrTail);
    while (!tail.empty() && (tail.back() == '\n' || tail.back() == '\r')) tail.pop_back();
    if (!tail.empty()) message += "; ffmpeg said: " + tail;
    throw VideoError(message);
}

void VideoEncoder::AddPng(const std::filesystem::path& png) {
    std::ifstream in(png, std::ios::binary);
    std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (!in && !in.eof()) Fail("cannot read frame '" + png.string() + "'");
    if (bytes.empty()) Fail("frame '" + png.string() + "' is empty");
    if (!WriteAll(stdin_fd_, bytes.data(), bytes.size())) {
        Fail("ffmpeg stopped reading frames (at '" + png.string() + "')");
    }
}

void VideoEncoder::Finish() {
    ::close(stdin_fd_);
    stdin_fd_ = -1;
    const int status = Wait();
    stderr_reader_.join();
    if (!(WIFEXITED(status) && WEXITSTATUS(status) == 0)) {
        Fail(WIFEXITED(status) ? fmt::format("ffmpeg exited with status {}", WEXITSTATUS(status))
                               : fmt::format("ffmpeg was killed by signal {}", WTERMSIG(status)));
    }
    std::error_code error;
    std::filesystem::rename(partial_, output_, error);
    if (error) Fail("cannot rename '" + partial_.string() + "' to it: " + error.message());
    finished_ = true;
}

}  // namespace zenith::sim
