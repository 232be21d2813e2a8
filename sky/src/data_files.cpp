#include "data_files.h"

#include <algorithm>
#include <cerrno>
#include <fstream>
#include <sstream>
#include <system_error>
#include <vector>

#include "zenith/base/json_text.h"

namespace zenith::sky::data_files {

std::string Quote(std::string_view text) {
    std::string quoted(1, '\'');
    quoted.append(text);
    quoted.push_back('\'');
    return quoted;
}

std::string LineColumn(std::string_view text, std::size_t byte) {
    byte = std::min(byte, text.size());
    const std::string_view before = text.substr(0, byte);
    const std::size_t line =
        1 + static_cast<std::size_t>(std::count(before.begin(), before.end(), '\n'));
    const std::size_t line_start = before.rfind('\n');
    const std::size_t column = line_start == std::string_view::npos ? byte + 1 : byte - line_start;
    return std::to_string(line) + ":" + std::to_string(column);
}

std::string JsonSyntaxMessage(std::string_view source, std::string_view text, std::size_t position,
                              std::string what) {
    if (const std::size_t at = what.find("] "); at != std::string::npos) {
        what = what.substr(at + 2);
    }
    std::string message(source);
    message.append(":").append(LineColumn(text, position == 0 ? 0 : position - 1));
    message.append(": JSON syntax: ").append(what);
    return message;
}

std::string JsonExceptionMessage(std::string_view source, std::string what) {
    if (const std::size_t at = what.find("] "); at != std::string::npos) {
        what = what.substr(at + 2);
    }
    return std::string(source) + ": " + what;
}

std::string JsonDepthProblem(std::string_view source, std::string_view text) {
    const std::optional<std::size_t> at = FindJsonNestingBeyond(text, kMaxJsonDepth);
    if (!at) return {};
    return std::string(source) + ":" + LineColumn(text, *at) + ": JSON nested deeper than " +
           std::to_string(kMaxJsonDepth) + " levels (a data file needs a few)";
}

bool ReadNamedJsonFile(std::string_view name_or_path, const std::filesystem::path& directory,
                       std::string_view kind, std::string_view directory_note, NamedFile& file,
                       std::string& error) {
    const std::string text(name_or_path);
    const bool is_path =
        text.find('/') != std::string::npos || (text.size() > 5 && text.ends_with(".json"));
    if (text.empty()) {
        error = "empty " + std::string(kind) + " name";
        return false;
    }
    file.path = is_path ? std::filesystem::path(text) : directory / (text + ".json");
    std::ifstream in(file.path, std::ios::binary);
    if (!in) {
        error = "cannot open " + std::string(kind) + " file " + Quote(file.path.string()) + ": " +
                std::generic_category().message(errno);
        if (!is_path) {
            std::vector<std::string> stems;
            std::error_code ignored;
            for (const auto& entry : std::filesystem::directory_iterator(directory, ignored)) {
                if (entry.path().extension() == ".json") stems.push_back(entry.path().stem());
            }
            std::sort(stems.begin(), stems.end());
            std::string names;
            for (const std::string& stem : stems) names += (names.empty() ? "" : ", ") + stem;
            error += "; expected a " + std::string(kind) + " preset (" +
                     (names.empty() ? "none found" : names) + " in " + directory.string() +
                     (directory_note.empty() ? "" : ", " + std::string(directory_note)) +
                     ") or a path to a .json file";
        }
        return false;
    }
    std::error_code size_error;
    const std::uintmax_t size = std::filesystem::file_size(file.path, size_error);
    if (!size_error && size > kMaxJsonBytes) {
        error = std::string(kind) + " file " + Quote(file.path.string()) + " has " +
                std::to_string(size) + " bytes (a data file has at most " +
                std::to_string(kMaxJsonBytes) + ")";
        return false;
    }
    std::ostringstream contents;
    contents << in.rdbuf();
    file.text = contents.str();
    return true;
}

}  // namespace zenith::sky::data_files
