#include "zenith/base/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string>

namespace zenith {
namespace {

[[noreturn]] void Fail(const std::filesystem::path& path, const std::string& cause) {
    std::string message = "cannot write '";
    message += path.string();
    message += "': ";
    message += cause;
    throw FileError(message);
}

std::string ErrnoText(int error) { return std::strerror(error); }

class FileDescriptor {
  public:
    explicit FileDescriptor(int fd) : fd_(fd) {}
    ~FileDescriptor() {
        if (fd_ >= 0) ::close(fd_);
    }
    FileDescriptor(const FileDescriptor&) = delete;
    FileDescriptor& operator=(const FileDescriptor&) = delete;
    int get() const { return fd_; }
    // Closes now and reports close()'s error: on NFS and some full disks it is the first to fail.
    int Close() {
        const int result = ::close(fd_);
        fd_ = -1;
        return result;
    }

  private:
    int fd_;
};

}  // namespace

void WriteFileAtomically(const std::filesystem::path& path, std::string_view bytes) {
    if (path.filename().empty()) Fail(path, "the path names no file");
    std::filesystem::path partial = path;
    partial += ".partial";
    // Appended, not "'" + s + "'": g++ 12 reports a false -Wrestrict on that at -O3.
    std::string quoted_partial = "'";
    quoted_partial += partial.string();
    quoted_partial += '\'';

    const int fd =
        ::open(partial.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);  // umask applies
    if (fd < 0) {
        const int error = errno;
        Fail(path, "cannot create " + quoted_partial + ": " + ErrnoText(error));
    }
    FileDescriptor file(fd);
    auto fail_and_remove = [&](const std::string& cause) {
        if (file.get() >= 0) file.Close();
        std::error_code ignored;
        std::filesystem::remove(partial, ignored);
        Fail(path, cause);
    };

    std::size_t written = 0;
    while (written < bytes.size()) {
        const ssize_t n = ::write(file.get(), bytes.data() + written, bytes.size() - written);
        if (n < 0) {
            if (errno == EINTR) continue;
            const int error = errno;
            fail_and_remove("writing " + quoted_partial + " failed after " +
                            std::to_string(written) + " of " + std::to_string(bytes.size()) +
                            " bytes: " + ErrnoText(error));
        }
        written += static_cast<std::size_t>(n);
    }
    if (::fsync(file.get()) != 0) {
        const int error = errno;
        fail_and_remove("fsync of " + quoted_partial + " failed: " + ErrnoText(error));
    }
    if (file.Close() != 0) {
        const int error = errno;
        fail_and_remove("closing " + quoted_partial + " failed: " + ErrnoText(error));
    }
    if (::rename(partial.c_str(), path.c_str()) != 0) {
        const int error = errno;
        fail_and_remove("renaming " + quoted_partial + " to it failed: " + ErrnoText(error));
    }
    // Make the rename itself durable. Best effort: some file systems refuse fsync on directories,
    // and by now the new file is complete under its final name either way.
    const std::filesystem::path directory =
        path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
    const int dir_fd = ::open(directory.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (dir_fd >= 0) {
        ::fsync(dir_fd);
        ::close(dir_fd);
    }
}

}  // namespace zenith
