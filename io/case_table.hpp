// SPDX-License-Identifier: BSD-3-Clause
// A case file as a TOML table (toml++), for a caller that edits it before it
// is read: the Python module sets keys of a case file in its parsed table
// (io/case_file.hpp reads a case from a file or a text).  The table keeps
// each node's source, so a message names the line of the case file, and
// for a node set from elsewhere the name of its source instead: a node
// parsed with the source name "override 'material.E'" is named
// "case.toml: override 'material.E'" (io/case_section.hpp, node_place).
#pragma once

#include <string>
#include <toml++/toml.h>

#include "io/case_file.hpp"

namespace igac {

// The text of a case file parsed; throws InputError naming `path` and the
// line (malformed TOML, a key of too many dotted parts).
toml::table parse_case_text(const std::string& text, const std::string& path);
// read_case_text of a parsed (and perhaps edited) case.
CaseSpec read_case_table(const toml::table& root, const std::string& path);

}  // namespace igac
