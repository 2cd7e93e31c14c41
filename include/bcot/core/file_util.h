// File helpers. Every output bcot writes goes through WriteFileAtomic (temp file in the same
// directory, fsync, rename), so a killed process never leaves a half-written file behind.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "bcot/core/status.h"

namespace bcot {

// The whole file, byte for byte. Errors: "<path>: <reason>" (kNotFound for a missing file,
// kIoError for a directory or a failed read).
StatusOr<std::string> ReadTextFile(const std::string& path);

// Same, with the reason alone as the error message ("file not found", "is a directory, expected
// a file", ...), for callers that phrase the error around the path themselves.
StatusOr<std::string> ReadFileContents(const std::string& path);

// Writes `content` to `path` atomically; creates missing parent directories.
Status WriteFileAtomic(const std::string& path, const std::string& content);

// Creates `path` and its parents (no error if it exists).
Status CreateDirectories(const std::string& path);

// Creates `dir` (and its parents) if missing and proves that files can be created in it (a
// probe file is created and removed): an output directory is checked before hours of work are
// spent on what it will hold. Errors name the directory and the reason.
Status CheckWritableDirectory(const std::string& dir);

// `relative` resolved against the directory holding `file` (absolute paths pass through).
std::string ResolveRelativeTo(const std::string& file, const std::string& relative);

// Text helpers shared by the readers.

// Splits `text` at '\n' and drops one trailing '\r' per line (CRLF files). A final line end
// does not start another line: "a\nb\n" and "a\nb" both give {"a", "b"}. A UTF-8 byte-order
// mark at the start (files saved by some Windows editors) is dropped.
std::vector<std::string> SplitLines(const std::string& text);

// Splits at any run of the characters in `separators`; no empty tokens.
std::vector<std::string> SplitTokens(std::string_view text, std::string_view separators);

// `text` without leading and trailing spaces, tabs and '\r'.
std::string_view TrimWhitespace(std::string_view text);

// Locale-independent parsing of an entire token (a leading '+' is allowed, nothing else may
// surround the number). ParseDouble accepts "nan"/"inf"; callers check finiteness. False when
// the token is not a number or is out of range.
bool ParseDouble(std::string_view text, double* value);
bool ParseInt64(std::string_view text, int64_t* value);

}  // namespace bcot
