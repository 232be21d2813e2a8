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

#include "zenith/base/json_value.h"

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

// Data files are small; a larger file or a deeper nesting is refused before it can cost much
// (a deep nesting would overflow the stack of any recursive walk).
inline constexpr std::size_t kMaxJsonBytes = 16u << 20;
inline constexpr int kMaxJsonDepth = 32;

// "source: <what>" for a JSON exception, without nlohmann's "[json.exception...]" prefix: for
// the errors a reader's own checks do not catch first (a number too large for a double).
std::string JsonExceptionMessage(std::string_view source, std::string what);

// Throws Error("source:line:column: JSON nested deeper than kMaxJsonDepth levels") when the text
// nests arrays and objects deeper than that (a linear scan that knows strings, before any parser
// recurses or builds anything).
std::string JsonDepthProblem(std::string_view source, std::string_view text);
template <class Error>
void CheckJsonDepth(std::string_view source, std::string_view text) {
    if (std::string problem = JsonDepthProblem(source, text); !problem.empty()) {
        throw Error(problem);
    }
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
        for (const auto& item : object.items()) {
            const std::string& key = item.key();
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
