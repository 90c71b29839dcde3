// SPDX-License-Identifier: BSD-3-Clause
// Reading an input file whole: a case file, a geometry file, a restart's
// state files and the .pvd it continues, an output folder's manifest.  One
// guarded reader for all of them, so that none hangs on a FIFO, reads
// /dev/zero until the memory runs out, or ends in a library's words for a
// folder: regular files only (a symbolic link to one is one), at most a size
// fixed per kind of file, and otherwise an InputError of one line naming the
// file and why.  And FNV-1a, the hash igac keeps of what it read or wrote.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "model/case_spec.hpp"  // InputError

namespace igac {

// What a file is, for messages, and the most bytes one may hold: far above
// any real one, so that only something that is not one is refused.
struct InputFileKind {
  const char* what;        // "case file"
  std::uint64_t max_bytes;
};
inline constexpr InputFileKind kCaseFile{"case file", std::uint64_t(16) << 20};       // a few kB in practice
inline constexpr InputFileKind kGeometryFile{"geometry file", std::uint64_t(1) << 30};  // ~10 MB per 100k points
inline constexpr InputFileKind kStateFile{"state file", std::uint64_t(4) << 30};       // 16 bytes per unknown, plus histories
inline constexpr InputFileKind kPvdFile{"ParaView collection (.pvd)", std::uint64_t(256) << 20};  // ~100 bytes per step and part
inline constexpr InputFileKind kManifestFile{"output folder's manifest", std::uint64_t(16) << 20};

// The bytes of the regular file `path`.  Throws InputError: "PATH: no such
// case file", "PATH: not a regular file (a folder, FIFO or device): a case
// file must be a regular file", "PATH: N bytes, more than a case file holds
// (at most M)", "PATH: cannot read the case file (the system's reason)", and
// for a path with a NUL character in it (the Python module's strings may
// hold one; the system would read the path up to it, another file).
std::string read_input_file(const std::string& path, const InputFileKind& kind);

// FNV-1a, 64 bits (not a cryptographic hash).  Every step is a bijection of
// the running state, so two inputs of one length that differ in one byte
// never hash alike: a flipped bit is always caught.
std::uint64_t fnv1a64(std::string_view bytes);

}  // namespace igac
