#include "farm/wire.hpp"

#include <cstdint>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <type_traits>

namespace grip::farm {
namespace {

class Writer {
 public:
  template <typename T>
  void value(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    bytes_.append(reinterpret_cast<const char*>(&v), sizeof v);
  }
  template <typename T>
  void values(const T* data, std::size_t count) {
    value<std::uint64_t>(count);
    if (count > 0) bytes_.append(reinterpret_cast<const char*>(data), count * sizeof(T));
  }
  template <typename T>
  void vector(const std::vector<T>& v) {
    values(v.data(), v.size());
  }
  void text(const std::string& s) { values(s.data(), s.size()); }
  std::string take() { return std::move(bytes_); }

 private:
  std::string bytes_;
};

class Reader {
 public:
  explicit Reader(std::string_view bytes) : bytes_(bytes) {}
  template <typename T>
  T value() {
    T v;
    take(&v, sizeof v);
    return v;
  }
  template <typename T>
  std::vector<T> vector() {
    std::vector<T> v(count(sizeof(T)));
    take(v.data(), v.size() * sizeof(T));
    return v;
  }
  std::string text() {
    std::string s(count(1), '\0');
    take(s.data(), s.size());
    return s;
  }
  template <typename Matrix>
  void matrix(Matrix& m, Eigen::Index columns) {
    const std::vector<typename Matrix::Scalar> v = vector<typename Matrix::Scalar>();
    m.resize(static_cast<Eigen::Index>(v.size()) / columns, columns);
    if (!v.empty()) std::memcpy(m.data(), v.data(), v.size() * sizeof(typename Matrix::Scalar));
  }
  bool done() const { return offset_ == bytes_.size(); }

 private:
  std::size_t count(std::size_t element) {
    const auto n = value<std::uint64_t>();
    if (n > (bytes_.size() - offset_) / element)
      throw std::runtime_error("farm: truncated message");
    return static_cast<std::size_t>(n);
  }
  // An empty vector's data() may be null, and memcpy from or to null is undefined even for
  // no bytes (UBSan reports it): nothing is copied then.
  void take(void* out, std::size_t n) {
    if (n > bytes_.size() - offset_) throw std::runtime_error("farm: truncated message");
    if (n == 0) return;
    std::memcpy(out, bytes_.data() + offset_, n);
    offset_ += n;
  }
  std::string_view bytes_;
  std::size_t offset_ = 0;
};

}  // namespace

std::string pack(const io::ObjectRecord& r) {
  Writer w;
  w.text(r.name);
  w.text(r.category);
  w.value(r.scale);
  w.value<std::uint8_t>(r.soft);
  w.value(r.material);
  w.vector(r.vertices);
  w.vector(r.triangles);
  w.vector(r.tets);
  return w.take();
}

io::ObjectRecord unpack_object(std::string_view bytes) {
  Reader in(bytes);
  io::ObjectRecord r;
  r.name = in.text();
  r.category = in.text();
  r.scale = in.value<double>();
  r.soft = in.value<std::uint8_t>() != 0;
  r.material = in.value<io::Material>();
  r.vertices = in.vector<double>();
  r.triangles = in.vector<std::int32_t>();
  r.tets = in.vector<std::int32_t>();
  if (!in.done()) throw std::runtime_error("farm: trailing bytes in an object message");
  return r;
}

std::string pack(const std::vector<synth::Candidate>& candidates) {
  Writer w;
  w.value<std::uint64_t>(candidates.size());
  for (const synth::Candidate& c : candidates) {
    w.value(c.gripper);
    w.value<std::uint64_t>(c.hands.size());
    for (const synth::HandGrasp& hand : c.hands) {
      w.values(hand.pose.matrix().data(), 16);
      w.values(hand.joints.data(), static_cast<std::size_t>(hand.joints.size()));
      w.values(hand.contacts.data(), static_cast<std::size_t>(hand.contacts.size()));
      w.values(hand.contact_normals.data(), static_cast<std::size_t>(hand.contact_normals.size()));
    }
    w.value<std::uint64_t>(c.energies.size());
    for (const synth::EnergyTerm& e : c.energies) {
      w.text(e.name);
      w.value(e.value);
    }
    w.value(c.min_distance);
  }
  return w.take();
}

std::vector<synth::Candidate> unpack_candidates(std::string_view bytes) {
  Reader in(bytes);
  std::vector<synth::Candidate> candidates(in.value<std::uint64_t>());
  for (synth::Candidate& c : candidates) {
    c.gripper = in.value<grippers::GripperKind>();
    c.hands.resize(in.value<std::uint64_t>());
    for (synth::HandGrasp& hand : c.hands) {
      Eigen::Matrix4d pose;
      in.matrix(pose, 4);
      hand.pose.matrix() = pose;
      Eigen::MatrixXd joints;
      in.matrix(joints, 1);
      hand.joints = joints.col(0);
      in.matrix(hand.contacts, 3);
      in.matrix(hand.contact_normals, 3);
    }
    c.energies.resize(in.value<std::uint64_t>());
    for (synth::EnergyTerm& e : c.energies) {
      e.name = in.text();
      e.value = in.value<double>();
    }
    c.min_distance = in.value<double>();
  }
  if (!in.done()) throw std::runtime_error("farm: trailing bytes in a candidate message");
  return candidates;
}

void broadcast(std::string& bytes, int root, MPI_Comm comm) {
  std::uint64_t size = bytes.size();
  MPI_Bcast(&size, 1, MPI_UINT64_T, root, comm);
  bytes.resize(size);
  // MPI counts are int: send in chunks below 1 GiB.
  constexpr std::uint64_t kChunk = std::uint64_t{1} << 30;
  for (std::uint64_t offset = 0; offset < size; offset += kChunk) {
    const int n = static_cast<int>(std::min(kChunk, size - offset));
    MPI_Bcast(bytes.data() + offset, n, MPI_CHAR, root, comm);
  }
}

std::string first_error(const std::string& error, MPI_Comm comm) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  int failed = error.empty() ? size : rank;
  MPI_Allreduce(MPI_IN_PLACE, &failed, 1, MPI_INT, MPI_MIN, comm);
  if (failed == size) return {};
  std::string shared = error;
  broadcast(shared, failed, comm);
  return shared;
}

}  // namespace grip::farm
