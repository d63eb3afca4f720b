#include "src/synth/candidate_file.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

namespace grip::synth {
namespace {

constexpr const char* kMagic = "grip-candidates";
// Version 2 names the object (version 1 did not, so a trial could build another object).
constexpr int kVersion = 2;

std::string number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", value);
  return text;
}

// Reads one line's tokens with errors that name the file and line.
class LineReader {
 public:
  LineReader(std::istream& in, std::filesystem::path file) : in_(in), file_(std::move(file)) {}

  // Moves to the next non-empty, non-comment line and checks its first word.
  void next(const std::string& keyword) {
    std::string line;
    while (std::getline(in_, line)) {
      ++line_number_;
      if (line.empty() || line[0] == '#') continue;
      tokens_.clear();
      tokens_.str(line);
      std::string word;
      tokens_ >> word;
      if (word != keyword) fail("expected '" + keyword + "', found '" + word + "'");
      return;
    }
    fail("expected '" + keyword + "', found the end of the file");
  }

  double real(const std::string& what) {
    std::string word;
    if (!(tokens_ >> word)) fail("missing " + what);
    try {
      std::size_t used = 0;
      const double value = std::stod(word, &used);
      if (used != word.size()) throw std::invalid_argument(word);
      if (!std::isfinite(value)) throw std::invalid_argument(word);
      return value;
    } catch (const std::exception&) {
      fail(what + " '" + word + "' is not a finite number");
    }
  }

  // A point of the candidate's field `what`, in the object's frame, within the bound.
  void near_object(const Eigen::Vector3d& point, const std::string& what) {
    if (point.stableNorm() <= kMaxCandidateDistance) return;
    char distance[32];
    std::snprintf(distance, sizeof distance, "%.3g m", point.stableNorm());
    fail(what + " lies " + distance + " from the object's origin; a candidate must lie within " +
         std::to_string(static_cast<int>(kMaxCandidateDistance)) + " m of it");
  }

  int count(const std::string& what) {
    const double value = real(what);
    if (value < 0 || value != std::floor(value) || value > 1e9) {
      fail(what + " must be a non-negative integer");
    }
    return static_cast<int>(value);
  }

  // A count of `per_item` numbers or words each that the rest of the line must hold: checked
  // before anything is allocated for them.
  int count_on_line(const std::string& what, int per_item) {
    const int value = count(what);
    const std::streampos here = tokens_.tellg();
    std::int64_t left = 0;
    for (std::string token; tokens_ >> token;) ++left;
    tokens_.clear();
    tokens_.seekg(here);
    if (static_cast<std::int64_t>(value) * per_item > left) {
      fail(what + " is " + std::to_string(value) + " but the line holds only " +
           std::to_string(left) + " values after it");
    }
    return value;
  }

  // The rest of the line, without its leading blank (a path may hold spaces).
  std::string rest(const std::string& what) {
    std::string text;
    std::getline(tokens_, text);
    if (!text.empty() && text.front() == ' ') text.erase(0, 1);
    if (text.empty()) fail("missing " + what);
    return text;
  }

  std::string word(const std::string& what) {
    std::string word;
    if (!(tokens_ >> word)) fail("missing " + what);
    return word;
  }

  // The line's next word, or "" at its end.
  std::string word_or_end() {
    std::string word;
    tokens_ >> word;
    return word;
  }

  void expect(const std::string& keyword) {
    if (word(keyword) != keyword) fail("expected '" + keyword + "'");
  }

  void end() {
    std::string extra;
    if (tokens_ >> extra) fail("unexpected '" + extra + "' at the end of the line");
  }

  // Fails if anything but blank lines and comments follows.
  void finish() {
    std::string line;
    while (std::getline(in_, line)) {
      ++line_number_;
      if (!line.empty() && line[0] != '#') fail("more lines than the header's count");
    }
  }

  [[noreturn]] void fail(const std::string& message) const {
    throw std::runtime_error(file_.string() + ":" + std::to_string(line_number_) + ": " + message +
                             " (a candidate file written by 'grip synth' was expected; see "
                             "docs/synthesis.md)");
  }

 private:
  std::istream& in_;
  std::filesystem::path file_;
  std::istringstream tokens_;
  int line_number_ = 0;
};

}  // namespace

void write_candidates(const std::filesystem::path& file, const CandidateObject& object,
                      const grippers::GripperType& gripper,
                      const std::vector<Candidate>& candidates) {
  const std::size_t hands = candidates.empty() ? 1 : candidates[0].hands.size();
  const std::vector<EnergyTerm> first_terms =
      candidates.empty() ? std::vector<EnergyTerm>{} : candidates[0].energies;
  for (const Candidate& c : candidates) {
    bool same_names = c.energies.size() == first_terms.size();
    for (std::size_t i = 0; same_names && i < first_terms.size(); ++i) {
      same_names = c.energies[i].name == first_terms[i].name;
    }
    if (c.gripper != gripper.kind || c.hands.size() != hands || !same_names) {
      throw std::invalid_argument(
          "write_candidates: all candidates of one file must share the "
          "gripper, the hand count and the energy terms");
    }
  }
  std::ofstream out(file);
  if (!out) throw std::runtime_error(file.string() + ": cannot open for writing");
  out << "# grip synthesized grasp candidates (docs/synthesis.md)\n";
  out << kMagic << ' ' << kVersion << '\n';
  out << "object seed " << object.seed << " scale " << number(object.scale) << " hash "
      << (object.content_hash.empty() ? "-" : object.content_hash) << " spec " << object.spec
      << '\n';
  out << "gripper " << gripper.name
      << (gripper.kind == grippers::GripperKind::kDescribed ? " described" : "") << '\n';
  out << "hands " << hands << '\n';
  out << "joints " << gripper.joints << '\n';
  out << "energies " << first_terms.size();
  for (const EnergyTerm& term : first_terms) out << ' ' << term.name;
  out << '\n';
  out << "count " << candidates.size() << '\n';
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    const Candidate& c = candidates[i];
    out << "candidate " << i << " min_distance " << number(c.min_distance) << " energy";
    for (const EnergyTerm& term : c.energies) out << ' ' << number(term.value);
    out << '\n';
    for (const HandGrasp& hand : c.hands) {
      if (hand.joints.size() != gripper.joints ||
          hand.contacts.rows() != hand.contact_normals.rows()) {
        throw std::invalid_argument("write_candidates: candidate " + std::to_string(i) +
                                    " has the wrong number of joints or contact normals");
      }
      const Eigen::Quaterniond q(hand.pose.linear());
      const Eigen::Quaterniond unit =
          (q.w() < 0 ? Eigen::Quaterniond(-q.coeffs()) : q).normalized();
      out << "hand position";
      for (int k = 0; k < 3; ++k) out << ' ' << number(hand.pose.translation()(k));
      out << " quaternion " << number(unit.w()) << ' ' << number(unit.x()) << ' '
          << number(unit.y()) << ' ' << number(unit.z()) << " matrix";
      for (const double v : pose_row_major(hand.pose)) out << ' ' << number(v);
      out << " joints";
      for (int k = 0; k < hand.joints.size(); ++k) out << ' ' << number(hand.joints(k));
      out << " contacts " << hand.contacts.rows();
      for (int r = 0; r < hand.contacts.rows(); ++r) {
        for (int k = 0; k < 3; ++k) out << ' ' << number(hand.contacts(r, k));
        for (int k = 0; k < 3; ++k) out << ' ' << number(hand.contact_normals(r, k));
      }
      out << '\n';
    }
  }
  if (!out.flush()) throw std::runtime_error(file.string() + ": write failed");
}

CandidateFile read_candidates(const std::filesystem::path& file) {
  if (std::filesystem::is_directory(file)) {
    throw std::runtime_error(file.string() + ": is a directory, not a candidate file");
  }
  std::ifstream in(file);
  if (!in) throw std::runtime_error(file.string() + ": cannot open the candidate file");
  LineReader reader(in, file);
  reader.next(kMagic);
  if (reader.count("format version") != kVersion) {
    reader.fail("unsupported format version (this grip reads version " + std::to_string(kVersion) +
                "; version 1 files do not name their object: synthesize them again)");
  }
  reader.end();
  CandidateFile result;
  reader.next("object");
  reader.expect("seed");
  const std::string seed = reader.word("seed");
  if (seed.empty() || seed.find_first_not_of("0123456789") != std::string::npos) {
    reader.fail("the seed '" + seed + "' is not a non-negative integer");
  }
  try {
    result.object.seed = std::stoull(seed);
  } catch (const std::out_of_range&) {
    reader.fail("the seed '" + seed + "' is too large");
  }
  reader.expect("scale");
  result.object.scale = reader.real("scale");
  if (!(result.object.scale > 0) || !std::isfinite(result.object.scale)) {
    reader.fail("the scale must be positive");
  }
  reader.expect("hash");
  result.object.content_hash = reader.word("hash");
  if (result.object.content_hash == "-") result.object.content_hash.clear();
  reader.expect("spec");
  result.object.spec = reader.rest("object spec");
  // A described gripper's name carries the word "described": its type is its file's, which
  // the trial is given (grip trial --gripper FILE.toml); a built-in name is checked here.
  reader.next("gripper");
  result.gripper = reader.word("gripper name");
  const std::string marker = reader.word_or_end();
  const grippers::GripperType* gripper = nullptr;
  if (marker.empty()) {
    try {
      gripper = &grippers::gripper_type(result.gripper);
    } catch (const std::invalid_argument& e) {
      reader.fail(e.what());
    }
  } else if (marker != "described") {
    reader.fail("unexpected '" + marker + "' after the gripper's name (only 'described' may be)");
  }
  reader.end();
  const grippers::GripperKind kind = gripper ? gripper->kind : grippers::GripperKind::kDescribed;
  const int joints = gripper ? gripper->joints : 1;  // a described gripper is a parallel one
  reader.next("hands");
  const int hands = reader.count("hand count");
  if (hands < 1 || hands > 2) reader.fail("hands must be 1 or 2");
  reader.end();
  reader.next("joints");
  if (reader.count("joint count") != joints) {
    reader.fail("joints must be " + std::to_string(joints) + " for " + result.gripper);
  }
  reader.end();
  reader.next("energies");
  std::vector<std::string> names(static_cast<std::size_t>(reader.count_on_line("energy count", 1)));
  for (std::string& name : names) name = reader.word("energy name");
  reader.end();
  reader.next("count");
  const int count = reader.count("candidate count");
  if (count > kMaxCandidates) {
    reader.fail("candidate count " + std::to_string(count) + " is more than the " +
                std::to_string(kMaxCandidates) + " a candidate file may hold");
  }
  reader.end();

  // Grown as candidates are read, so that a count the lines do not back allocates nothing.
  std::vector<Candidate>& candidates = result.candidates;
  for (int i = 0; i < count; ++i) {
    Candidate& c = candidates.emplace_back();
    c.gripper = kind;
    reader.next("candidate");
    if (reader.count("candidate index") != i)
      reader.fail("candidate index must be " + std::to_string(i));
    reader.expect("min_distance");
    c.min_distance = reader.real("min_distance");
    reader.expect("energy");
    for (const std::string& name : names)
      c.energies.push_back({name, reader.real("energy " + name)});
    reader.end();
    for (int h = 0; h < hands; ++h) {
      HandGrasp hand;
      reader.next("hand");
      reader.expect("position");
      Eigen::Vector3d position;
      for (int k = 0; k < 3; ++k) position(k) = reader.real("position");
      reader.near_object(position, "position");
      reader.expect("quaternion");
      Eigen::Vector4d wxyz;
      for (int k = 0; k < 4; ++k) wxyz(k) = reader.real("quaternion");
      if (std::abs(wxyz.norm() - 1.0) > 1e-9)
        reader.fail("the quaternion is not a unit quaternion");
      reader.expect("matrix");
      for (int r = 0; r < 3; ++r) {
        for (int k = 0; k < 3; ++k) hand.pose.linear()(r, k) = reader.real("matrix entry");
        hand.pose.translation()(r) = reader.real("matrix entry");
      }
      const Eigen::Matrix3d from_quaternion =
          Eigen::Quaterniond(wxyz(0), wxyz(1), wxyz(2), wxyz(3)).toRotationMatrix();
      if ((from_quaternion - hand.pose.linear()).norm() > 1e-9 ||
          (position - hand.pose.translation()).norm() > 1e-12) {
        reader.fail("the matrix disagrees with the position and quaternion");
      }
      reader.expect("joints");
      hand.joints.resize(joints);
      for (int k = 0; k < hand.joints.size(); ++k) hand.joints(k) = reader.real("joint value");
      reader.expect("contacts");
      const int contacts = reader.count_on_line("contact count", 6);
      hand.contacts.resize(contacts, 3);
      hand.contact_normals.resize(contacts, 3);
      for (int r = 0; r < contacts; ++r) {
        for (int k = 0; k < 3; ++k) hand.contacts(r, k) = reader.real("contact point");
        reader.near_object(hand.contacts.row(r).transpose(), "contact point");
        for (int k = 0; k < 3; ++k) hand.contact_normals(r, k) = reader.real("contact normal");
      }
      reader.end();
      c.hands.push_back(std::move(hand));
    }
  }
  reader.finish();
  return result;
}

}  // namespace grip::synth
