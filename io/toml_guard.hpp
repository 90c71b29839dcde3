// SPDX-License-Identifier: BSD-3-Clause
// A check of a TOML text before toml++ parses it: toml++ limits the nesting
// of arrays and inline tables, but not the parts of a dotted key or a table
// header (`[a.a.a. ... .a]`), and walks the tree it built recursively, so a
// key of 100000 parts overflows the stack (SIGSEGV).  No case file needs
// more than a few parts.
#pragma once

#include <cctype>
#include <optional>
#include <string>
#include <string_view>

namespace igac {

inline constexpr int kMaxTomlKeyParts = 64;

// The 1-based line of the first key with more than kMaxTomlKeyParts parts,
// if any.  Dots inside strings and comments are not counted; a run of key
// characters, blanks, quoted parts and dots is one key (a number such as
// 1.5, a date with fractional seconds, has one dot).
inline std::optional<int> overlong_toml_key(std::string_view text) {
  int line = 1, dots = 0;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '\n') ++line;
    if (c == '"' || c == '\'') {  // a string (or a quoted key part): skip it
      const bool multi = text.substr(i, 3) == std::string(3, c);
      const std::string close = multi ? std::string(3, c) : std::string(1, c);
      size_t j = i + close.size();
      while (j < text.size() && text.substr(j, close.size()) != close) {
        if (c == '"' && text[j] == '\\') ++j;
        else if (text[j] == '\n') ++line;
        ++j;
      }
      i = j + close.size() - 1;
      continue;
    }
    if (c == '#') {  // a comment
      while (i + 1 < text.size() && text[i + 1] != '\n') ++i;
      continue;
    }
    if (c == '.') {
      if (++dots >= kMaxTomlKeyParts) return line;
    } else if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == ' ' || c == '\t')) {
      dots = 0;
    }
  }
  return std::nullopt;
}

}  // namespace igac
