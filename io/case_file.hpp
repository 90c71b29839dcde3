// SPDX-License-Identifier: BSD-3-Clause
// Case files: one TOML file per simulation (every key: docs/case_file.md).
// read_case() parses and validates everything it can without building the
// mesh; any problem is an InputError whose one-line message
// names the file, the key and the reason.
#pragma once

#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "model/case_spec.hpp"
#include "model/memory_estimate.hpp"  // apply_overrides
#include "model/solver_choice.hpp"    // check_petsc_case, check_preconditioner

namespace igac {

// Throws InputError.
CaseSpec read_case(const std::string& path);
// The same for a case file's text: `path` names it in messages, gives the
// default name and the folder that relative geometry files are read from
// (it need not exist).
CaseSpec read_case_text(const std::string& text, const std::string& path);
// Every key read_case accepts, sorted, as its path of tables: "name",
// "mesh.degree", "mesh.grading.direction", "contact.obstacle.radius";
// "faces.*" for the names of one's own in [faces].  Shapes, laws and
// obstacles contribute their registered keys.  docs/case_file.md documents
// each one (tests/unit/io/test_docs.cpp checks both ways).
std::vector<std::string> declared_case_keys();

// The candidate nearest to `word` by edit distance, when it is near enough
// to be a slip (at most a third of the word's letters, at least one):
// "did you mean" for unknown keys and subcommands.
std::optional<std::string> nearest_name(const std::string& word, const std::vector<std::string>& candidates);
// Why a case file's [solver] options cannot be given to PETSc ("" when they
// can): a case file may give only a few known options with checked values.
std::string check_case_petsc_options(const std::string& options);

}  // namespace igac
