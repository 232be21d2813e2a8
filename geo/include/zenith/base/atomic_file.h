// Files written so that a reader never sees half of one: the bytes go to "<path>.partial",
// are fsynced and renamed over path, so path is the old file or the complete new one even after
// a crash or a power loss.
#pragma once

#include <filesystem>
#include <string_view>

#include "zenith/base/error.h"

namespace zenith {

// Thrown when a file cannot be written; the message names the file and the system's reason.
class FileError : public Error {
  public:
    using Error::Error;
};

// Writes bytes atomically (see above). The partial file is removed on any error (only if this
// call created it). Throws FileError.
void WriteFileAtomically(const std::filesystem::path& path, std::string_view bytes);

}  // namespace zenith
