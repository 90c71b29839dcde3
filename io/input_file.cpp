// SPDX-License-Identifier: BSD-3-Clause
#include "io/input_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fmt/format.h>

namespace igac {

std::string read_input_file(const std::string& path, const InputFileKind& kind) {
  if (path.find('\0') != std::string::npos)
    throw InputError(fmt::format("{:?}: a file name with a NUL character in it: not a {}", path, kind.what));
  const auto cannot = [&](int err) {
    if (err == ENOENT) return InputError(fmt::format("{}: no such {}", path, kind.what));
    return InputError(fmt::format("{}: cannot read the {} ({})", path, kind.what, std::strerror(err)));
  };
  const auto not_regular = [&] {
    return InputError(fmt::format("{}: not a regular file (a folder, FIFO or device): a {} must be a regular file", path,
                                  kind.what));
  };
  const auto too_large = [&](std::uint64_t bytes) {
    return InputError(fmt::format("{}: {} bytes, more than a {} holds (at most {})", path, bytes, kind.what,
                                  kind.max_bytes));
  };
  // The kind of file first, without opening it: opening a device may do
  // something, and a FIFO's open waits for a writer.
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) throw cannot(errno);
  if (!S_ISREG(st.st_mode)) throw not_regular();
  if (std::uint64_t(st.st_size) > kind.max_bytes) throw too_large(std::uint64_t(st.st_size));
  // O_NONBLOCK: should the name have become a FIFO meanwhile, open returns
  // at once (and fstat below refuses it); on a regular file it changes nothing.
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) throw cannot(errno);
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{fd};
  if (::fstat(fd, &st) != 0) throw cannot(errno);
  if (!S_ISREG(st.st_mode)) throw not_regular();
  std::string bytes;
  bytes.reserve(size_t(st.st_size));
  char buf[1 << 16];
  while (true) {
    const ssize_t n = ::read(fd, buf, sizeof buf);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw cannot(errno);
    if (n == 0) break;
    bytes.append(buf, size_t(n));
    if (bytes.size() > kind.max_bytes) throw too_large(bytes.size());  // (it grew while read)
  }
  return bytes;
}

std::uint64_t fnv1a64(std::string_view bytes) {
  std::uint64_t h = 14695981039346656037ull;
  for (const char c : bytes) {
    h ^= static_cast<unsigned char>(c);
    h *= 1099511628211ull;
  }
  return h;
}

}  // namespace igac
