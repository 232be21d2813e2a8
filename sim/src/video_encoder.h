// PNG frames into an H.264 MP4 through ffmpeg, spawned with an argument vector (never a shell
// command line): no character of a path can run a command or change an option.
#pragma once

#include <sys/types.h>

#include <filesystem>
#include <string>
#include <thread>

#include "zenith/base/error.h"

namespace zenith::sim {

// ffmpeg cannot be started, fails, or a frame cannot be read; the message says which and ends
// with what ffmpeg printed.
class VideoError : public Error {
  public:
    using Error::Error;
};

class VideoEncoder {
  public:
    // Starts ffmpeg encoding PNG images from its standard input at `fps` frames per second into
    // "<output>.partial.mp4" (odd sizes are padded by one pixel: H.264 4:2:0 needs even ones).
    // Throws VideoError when ffmpeg is not installed or cannot be started.
    VideoEncoder(const std::filesystem::path& output, double fps);
    // Stops ffmpeg and removes the partial file unless Finish() succeeded.
    ~VideoEncoder();
    VideoEncoder(const VideoEncoder&) = delete;
    VideoEncoder& operator=(const VideoEncoder&) = delete;

    // Sends one PNG file's bytes as the next frame. Throws VideoError when it cannot be read or
    // ffmpeg has stopped reading.
    void AddPng(const std::filesystem::path& png);
    // Ends the input, waits for ffmpeg and renames the partial file to the output. Throws
    // VideoError with ffmpeg's exit status and its last messages when it failed.
    void Finish();

  private:
    [[noreturn]] void Fail(const std::string& what);
    int Wait();

    std::filesystem::path output_, partial_;
    pid_t pid_ = -1;
    int stdin_fd_ = -1;
    int stderr_fd_ = -1;
    std::thread stderr_reader_;
    std::string stderr_tail_;  // the last few KB of ffmpeg's messages
    bool finished_ = false;
};

}  // namespace zenith::sim
