// SPDX-License-Identifier: BSD-3-Clause
// state_NNNN.bin: the state after step NNNN of a run in steps, written next
// to the step's .vtu, what `igac run CASE --restart DIR` continues from
// (docs/design.md, "Restart").  A little binary file, little-endian, every
// integer an int64 and every real an IEEE-754 double, in this order:
//
//   "IGACSTEP"                       8 bytes, the magic
//   version                          5 (older ones are refused: run the case again;
//                                    4 had no checksum, 3 held the mixed formulation's
//                                    values per element)
//   case hash                        length, then its bytes: summary.json's input.fnv1a64
//   run options                      length, then its bytes: the options that change the
//                                    result (--refine, --degree, the solver's), one
//                                    "name=value" a line (app/restart.hpp, run_options)
//   step                             from 1
//   t, dt, dt_old                    the time reached, the next increment, the last one
//   x                                length, then the doubles: [u_free; lambda; lambda_t;
//                                    z_A per pressure function (mixed)]
//   x_old                            length, then the doubles (the state one step before)
//   record: load factor (t), Newton iterations, cut-backs, augmentations,
//           residual norms (length, doubles), active-set sizes (length, int64s)
//   point:  load factor, contact forces (length, doubles), face displacement,
//           obstacle displacement, reactions (count, then per face set:
//           name (length, bytes), force (length, doubles)), tangential
//           forces (count, then per contact: length, doubles)
//   friction history (FrictionHistory, contact/friction_state.hpp;
//           empty vectors without friction): position, slip, direction,
//           alpha (each length, doubles), state (length, int64s), Schur
//           batches (count, then each: length, int64s), from (double)
//   pressure multipliers             length, then the doubles, one per pressure function
//                                    (incompressible; else 0)
//   checksum                         8 bytes: FNV-1a 64 (io/input_file.hpp) of every byte
//                                    before it; a file whose bytes do not match is refused
//
// Written atomically (a temporary file renamed over the name), so a file
// that exists is whole; read back it gives the same doubles, bit for bit.
#pragma once

#include <string>

#include "model/case_spec.hpp"  // InputError
#include "model/run_result.hpp"

namespace igac {

// What run wrote a state file: its case file (hash) and the options given
// beside it that change the result.
struct StateOrigin {
  std::string case_hash;
  std::string options;
};

std::string state_file_name(int step);  // state_NNNN.bin
void write_state_file(const std::string& path, const StateOrigin& origin, const StepState& state);
// Throws InputError naming the file when it is not a regular file, not a
// state file of this version, or damaged (its checksum); `origin` receives
// what it was written with.
StepState read_state_file(const std::string& path, StateOrigin& origin);

}  // namespace igac
