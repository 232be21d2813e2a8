// Reading the JSON data files of sky/ (atmosphere presets, weather presets): one way to resolve
// a name or a path, and one style of error message (file:line:column, the value quoted).
#pragma once

#include <algorithm>
#include <cstddef>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <span>
#include <string>
#include <string_view>
#include <utility>

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

// A JSON value as an error message shows it: its type and its text, cut at 40 characters.
inline std::string Describe(const nlohmann::json& value) {
    std::string text = value.dump();
    if (text.size() > 40) text = text.substr(0, 37) + "...";
    return std::string(value.type_name()) + " " + text;
}

// The checks every data file makes on its JSON, failing with `Error` as
// "<source>: <key path>: <what>". Each file's reader derives from it and adds its own values.
template <class Error>
class JsonReader {
  public:
    explicit JsonReader(std::string source) : source_(std::move(source)) {}

    [[noreturn]] void Fail(const std::string& path, const std::string& what) const {
        throw Error(source_ + ": " + path + ": " + what);
    }

    void RejectUnknownKeys(const nlohmann::json& object, const std::string& prefix,
                           std::span<const char* const> allowed) const {
        for (const auto& [key, value] : object.items()) {
            if (std::none_of(allowed.begin(), allowed.end(),
                             [&](const char* k) { return key == k; })) {
                std::string list;
                for (const char* k : allowed) list += std::string(list.empty() ? "" : ", ") + k;
                Fail(prefix + key, "unknown key; expected one of: " + list);
            }
        }
    }

    const nlohmann::json& Required(const nlohmann::json& object, const std::string& prefix,
                                   const char* key) const {
        const auto it = object.find(key);
        if (it == object.end()) Fail(prefix + key, "missing (required)");
        return *it;
    }

  private:
    std::string source_;
};

}  // namespace zenith::sky::data_files
