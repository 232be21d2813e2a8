// Reading the JSON data files of sky/ (atmosphere presets, weather presets): one way to resolve
// a name or a path, and one style of error message (file:line:column, the value quoted).
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>

namespace zenith::sky::data_files {

// 'text' in quotes. Built by appending: "'" + std::string + "'" trips GCC 12's false
// -Wrestrict (bug 105329).
std::string Quote(std::string_view text);

// 1-based "line:column" of a byte offset, as editors count them.
std::string LineColumn(std::string_view text, std::size_t byte);

// "source:line:column: JSON syntax: ..." for a parser error at 1-based `position` (the character
// that stopped it), without nlohmann's "[json.exception...]" prefix.
std::string JsonSyntaxMessage(std::string_view source, std::string_view text, std::size_t position,
                              std::string what);

struct NamedFile {
    std::filesystem::path path;
    std::string text;
};

// `name_or_path` is a path when it contains '/' or ends in ".json", else a name looked up as
// <directory>/<name>.json. Returns false with `error` set ("cannot open <kind> file '...': why;
// expected a <kind> preset (names found in directory, <directory_note>) or a path to a .json
// file") when it cannot be read.
bool ReadNamedJsonFile(std::string_view name_or_path, const std::filesystem::path& directory,
                       std::string_view kind, std::string_view directory_note, NamedFile& file,
                       std::string& error);

}  // namespace zenith::sky::data_files
