// SPDX-License-Identifier: BSD-3-Clause
// Output files of a run: summary.json (keys in docs/design.md, "Outputs"), the pressure files.
// Files are written to a temporary name and renamed, so a file that exists
// is complete; a value that is not finite is written as null and turns the
// status into a failure, never a NaN that looks like a number.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "model/model.hpp"
#include "model/run_result.hpp"

namespace igac {

using Json = nlohmann::ordered_json;

// Writes text to path atomically (temporary file in the same folder, rename).
void write_file_atomically(const std::string& path, const std::string& text);
// Why `path` could not be written, `err` the errno of the failure (0: not
// known): a missing or read-only folder is said as such (it was blamed on a
// full disk), anything else as the system says it ("File too large").
std::string why_not_written(const std::string& path, int err);
// FNV-1a (64 bits) of a case file's bytes, as 16 hex digits: which input a
// summary came from (not a cryptographic hash).  Empty when it is not one
// that read_case would read (io/input_file.hpp).
std::string fnv1a64_of_file(const std::string& path);
// A number, or null when it is not finite.
Json finite_or_null(double v);
// A number for a CSV cell: 10 significant digits, or an empty cell where it
// is not finite (a failed run writes no "nan" or "inf").
std::string csv_number(double v, int digits = 10);
// True when some value in the tree is null (a non-finite number was stored).
bool has_null_value(const Json& j);

Json run_summary(const Model& model, const RunResult& result);
// Per multiplier and P1 re-interpolation of contact `contact` (case
// order): kind, r, pressure (and r/a, p/p0, Hertz when the case has Hertz
// as reference).
std::string pressure_csv(const RunResult& result, size_t contact = 0);
// What names each contact's files, in case order: "" for a case with one
// contact (pressure.csv, contact_0000.vtu); with several, the face name
// (its characters other than letters, digits, '-', '_' and '.' written as
// '_'; a name already taken gets _<its place in the case, from 1>).
std::vector<std::string> contact_file_tags(const Model& model);
// The names (without .csv / .svg) of each contact's pressure files, in case
// order: "pressure" with one contact, "pressure_<tag>" for each of several.
std::vector<std::string> pressure_file_stems(const Model& model);
// Large deformation: load factor, contact force (contact_force_<face> per
// contact when there are several), loaded-face displacement, obstacle travel.
std::string load_curve_csv(const Model& model, const RunResult& result);

}  // namespace igac
