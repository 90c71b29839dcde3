// SPDX-License-Identifier: BSD-3-Clause
#include "io/state_file.hpp"

#include <bit>
#include <cstdint>
#include <cstring>
#include <fmt/format.h>

#include "io/input_file.hpp"
#include "io/json_out.hpp"

namespace igac {
namespace {

static_assert(std::endian::native == std::endian::little, "state files are little-endian");
constexpr char kMagic[8] = {'I', 'G', 'A', 'C', 'S', 'T', 'E', 'P'};
// 2: the run options after the case hash; 3: the path-dependent history
// (friction, incompressible), the step's augmentations and tangential forces;
// 4: the mixed formulation's dilatations and multipliers per pressure block
// (since the pressure space, per pressure function: the same layout, a file
// of another count refused); 5: the checksum at the end (a file without one
// is refused: its numbers cannot be told from damaged ones).
constexpr int64_t kVersion = 5;
constexpr size_t kHead = sizeof kMagic + sizeof kVersion;  // magic and version
constexpr size_t kChecksum = sizeof(uint64_t);

struct Writer {
  std::string bytes;
  void raw(const void* p, size_t n) { bytes.append(static_cast<const char*>(p), n); }
  void integer(int64_t v) { raw(&v, sizeof v); }
  void real(double v) { raw(&v, sizeof v); }
  void text(const std::string& s) {
    integer(int64_t(s.size()));
    raw(s.data(), s.size());
  }
  template <class V>
  void reals(const V& v) {
    integer(int64_t(v.size()));
    for (auto x : v) real(double(x));
  }
  template <class V>
  void integers(const V& v) {
    integer(int64_t(v.size()));
    for (auto x : v) integer(int64_t(x));
  }
};

struct Reader {
  const std::string& path;
  std::string bytes;
  size_t at = 0;
  [[noreturn]] void fail(const std::string& why) const {
    throw InputError(fmt::format("{}: not a state file igac can restart from ({})", path, why));
  }
  void raw(void* p, size_t n) {
    if (bytes.size() - at < n) fail("cut short");
    std::memcpy(p, bytes.data() + at, n);
    at += n;
  }
  int64_t integer() {
    int64_t v;
    raw(&v, sizeof v);
    return v;
  }
  double real() {
    double v;
    raw(&v, sizeof v);
    return v;
  }
  size_t length() {
    const int64_t n = integer();
    if (n < 0 || uint64_t(n) > (bytes.size() - at)) fail("a length beyond the file");
    return size_t(n);
  }
  std::string text() {
    std::string s(length(), '\0');
    raw(s.data(), s.size());
    return s;
  }
  Eigen::VectorXd vector() {
    Eigen::VectorXd v(static_cast<Eigen::Index>(length()));
    for (Eigen::Index i = 0; i < v.size(); ++i) v[i] = real();
    return v;
  }
  std::vector<double> doubles() {
    const Eigen::VectorXd v = vector();
    return {v.begin(), v.end()};
  }
  std::vector<int64_t> integers() {
    std::vector<int64_t> v(length());  // (no more than the bytes left)
    for (int64_t& x : v) x = integer();
    return v;
  }
};

}  // namespace

std::string state_file_name(int step) { return fmt::format("state_{:04d}.bin", step); }

void write_state_file(const std::string& path, const StateOrigin& origin, const StepState& s) {
  Writer w;
  w.raw(kMagic, sizeof kMagic);
  w.integer(kVersion);
  w.text(origin.case_hash);
  w.text(origin.options);
  w.integer(s.step);
  w.real(s.driver.t);
  w.real(s.driver.dt);
  w.real(s.driver.dt_old);
  w.reals(s.driver.x);
  w.reals(s.driver.x_old);
  w.real(s.record.load_factor);
  w.integer(s.record.newton_iterations);
  w.integer(s.record.cut_backs);
  w.integer(s.record.augmentations);
  w.reals(s.record.residual_norms);
  w.integer(int64_t(s.record.active_set_sizes.size()));
  for (int a : s.record.active_set_sizes) w.integer(a);
  w.real(s.point.load_factor);
  w.reals(s.point.contact_forces);
  w.real(s.point.face_displacement);
  w.real(s.point.obstacle_displacement);
  w.integer(int64_t(s.point.dirichlet_reactions.size()));
  for (const FaceReaction& f : s.point.dirichlet_reactions) {
    w.text(f.face);
    w.reals(f.force);
  }
  w.integer(int64_t(s.point.tangential_forces.size()));
  for (const Eigen::VectorXd& f : s.point.tangential_forces) w.reals(f);
  const FrictionHistory& h = s.friction;
  w.reals(h.position);
  w.reals(h.slip);
  w.reals(h.direction);
  w.reals(h.alpha);
  w.integers(h.state);
  w.integer(int64_t(h.schur_batches.size()));
  for (const std::vector<int>& b : h.schur_batches) w.integers(b);
  w.real(h.from);
  w.reals(s.pressure_multipliers);
  const uint64_t checksum = fnv1a64(w.bytes);
  w.raw(&checksum, sizeof checksum);
  write_file_atomically(path, w.bytes);
}

StepState read_state_file(const std::string& path, StateOrigin& origin) {
  // (io/input_file.hpp: a folder, FIFO or device, or a file larger than any state, in one line)
  Reader r{path, read_input_file(path, kStateFile)};
  char magic[8];
  r.raw(magic, sizeof magic);
  if (std::memcmp(magic, kMagic, sizeof kMagic) != 0) r.fail("no IGACSTEP magic");
  // (2 lacks the friction and incompressible histories; 3 holds them per element; 4 has no checksum)
  if (const int64_t v = r.integer(); v < kVersion)
    r.fail(fmt::format("written by an older igac: state-file version {}, this igac reads {}; run the case again", v, kVersion));
  else if (v != kVersion)
    r.fail(fmt::format("version {}, this igac reads {}", v, kVersion));
  // Every byte checked before one is believed: a damaged length or number
  // is refused, not read as another state.
  if (r.bytes.size() < kHead + kChecksum) r.fail("cut short");
  uint64_t checksum;
  std::memcpy(&checksum, r.bytes.data() + r.bytes.size() - kChecksum, kChecksum);
  r.bytes.resize(r.bytes.size() - kChecksum);
  if (fnv1a64(r.bytes) != checksum) r.fail("damaged: its checksum does not match its contents, cut short or altered");
  origin.case_hash = r.text();
  origin.options = r.text();
  StepState s;
  s.step = int(r.integer());
  s.driver.t = r.real();
  s.driver.dt = r.real();
  s.driver.dt_old = r.real();
  s.driver.x = r.vector();
  s.driver.x_old = r.vector();
  s.record.load_factor = r.real();
  s.record.newton_iterations = int(r.integer());
  s.record.cut_backs = int(r.integer());
  s.record.augmentations = int(r.integer());
  s.record.residual_norms = r.doubles();
  const size_t n = r.length();
  for (size_t i = 0; i < n; ++i) s.record.active_set_sizes.push_back(int(r.integer()));
  s.point.load_factor = r.real();
  s.point.contact_forces = r.doubles();
  s.point.face_displacement = r.real();
  s.point.obstacle_displacement = r.real();
  const size_t faces = r.length();
  for (size_t i = 0; i < faces; ++i) {
    FaceReaction f;
    f.face = r.text();
    f.force = r.vector();
    s.point.dirichlet_reactions.push_back(std::move(f));
  }
  const size_t tangential = r.length();
  for (size_t i = 0; i < tangential; ++i) s.point.tangential_forces.push_back(r.vector());
  FrictionHistory& h = s.friction;
  h.position = r.vector();
  h.slip = r.vector();
  h.direction = r.vector();
  h.alpha = r.vector();
  for (int64_t v : r.integers()) {
    if (v < kOpen || v > kSlip) r.fail("a friction state beyond open, stick and slip");
    h.state.push_back(char(v));
  }
  const size_t batches = r.length();
  for (size_t i = 0; i < batches; ++i) {
    std::vector<int>& b = h.schur_batches.emplace_back();
    for (int64_t v : r.integers()) b.push_back(int(v));
  }
  h.from = r.real();
  s.pressure_multipliers = r.vector();
  if (r.at != r.bytes.size()) r.fail("bytes after the end");
  return s;
}

}  // namespace igac
