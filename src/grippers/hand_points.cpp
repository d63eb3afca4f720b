#include "src/grippers/hand_points.hpp"

#include <toml++/toml.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "src/grippers/number_text.hpp"

namespace grip::grippers {
namespace {

class EntryReader {
 public:
  EntryReader(const std::filesystem::path& file, const char* array, std::size_t index,
              const toml::node& node)
      : file_(file), array_(array), index_(index), node_(node) {}

  const toml::table& table() const {
    if (!node_.is_table()) fail("is not a table");
    return *node_.as_table();
  }

  std::string text(const char* key) const {
    const auto value = table()[key].value<std::string>();
    if (!value || value->empty()) fail(std::string("needs '") + key + "', a link name");
    return *value;
  }

  Eigen::Vector3d vector(const char* key) const {
    const toml::array* array = table()[key].as_array();
    Eigen::Vector3d v;
    if (array == nullptr || array->size() != 3) {
      fail(std::string("needs '") + key + "', an array of 3 numbers");
    }
    for (std::size_t i = 0; i < 3; ++i) {
      const auto x = (*array)[i].value<double>();
      if (!x || !std::isfinite(*x)) fail(std::string("'") + key + "' must hold 3 finite numbers");
      v[static_cast<Eigen::Index>(i)] = *x;
    }
    return v;
  }

  double number(const char* key) const {
    const auto x = table()[key].value<double>();
    if (!x || !std::isfinite(*x)) fail(std::string("needs '") + key + "', a finite number");
    return *x;
  }

  [[noreturn]] void fail(const std::string& what) const {
    throw std::runtime_error("hand points '" + file_.string() + "', line " +
                             std::to_string(node_.source().begin.line) + ": " + array_ + "[" +
                             std::to_string(index_) + "] " + what);
  }

 private:
  const std::filesystem::path& file_;
  const char* array_;
  std::size_t index_;
  const toml::node& node_;
};

const toml::array* entries(const toml::table& root, const char* key,
                           const std::filesystem::path& file) {
  const toml::node* node = root.get(key);
  if (node == nullptr) return nullptr;
  if (!node->is_array_of_tables()) {
    throw std::runtime_error("hand points '" + file.string() + "': '" + key +
                             "' must be an array of tables, written [[" + key + "]]");
  }
  return node->as_array();
}

std::string vector_text(const Eigen::Vector3d& v) {
  std::string text(1, '[');
  text += number_text(v.x()) + ", " + number_text(v.y()) + ", " + number_text(v.z());
  text += ']';
  return text;
}

}  // namespace

HandPoints read_hand_points(const std::filesystem::path& file) {
  if (!std::filesystem::is_regular_file(file)) {
    throw std::runtime_error("hand points file '" + file.string() + "' not found");
  }
  toml::table root;
  try {
    root = toml::parse_file(file.string());
  } catch (const toml::parse_error& e) {
    throw std::runtime_error("hand points '" + file.string() + "', line " +
                             std::to_string(e.source().begin.line) + ": " +
                             std::string(e.description()));
  }
  for (const auto& [key, node] : root) {
    if (key.str() != "contact" && key.str() != "keypoint") {
      throw std::runtime_error("hand points '" + file.string() + "', line " +
                               std::to_string(node.source().begin.line) + ": unknown key '" +
                               std::string(key.str()) + "'; expected [[contact]] or [[keypoint]]");
    }
  }
  HandPoints points;
  if (const toml::array* contacts = entries(root, "contact", file)) {
    for (std::size_t i = 0; i < contacts->size(); ++i) {
      const EntryReader entry(file, "contact", i, *contacts->get(i));
      ContactCandidate contact{entry.text("link"), entry.vector("position"),
                               entry.vector("normal")};
      if (std::abs(contact.normal.norm() - 1.0) > 1e-6)
        entry.fail("'normal' must be a unit vector");
      points.contacts.push_back(contact);
    }
  }
  if (const toml::array* keypoints = entries(root, "keypoint", file)) {
    for (std::size_t i = 0; i < keypoints->size(); ++i) {
      const EntryReader entry(file, "keypoint", i, *keypoints->get(i));
      PenetrationSphere sphere{entry.text("link"), entry.vector("center"), entry.number("radius")};
      if (!(sphere.radius > 0.0)) entry.fail("'radius' must be positive");
      points.keypoints.push_back(sphere);
    }
  }
  return points;
}

void write_hand_points(const std::filesystem::path& file, const HandPoints& points,
                       const std::string& header_comment) {
  std::ostringstream text;
  std::istringstream comment(header_comment);
  for (std::string line; std::getline(comment, line);) text << "# " << line << '\n';
  for (const ContactCandidate& c : points.contacts) {
    text << "\n[[contact]]\nlink = \"" << c.link << "\"\nposition = " << vector_text(c.position)
         << "\nnormal = " << vector_text(c.normal) << '\n';
  }
  for (const PenetrationSphere& s : points.keypoints) {
    text << "\n[[keypoint]]\nlink = \"" << s.link << "\"\ncenter = " << vector_text(s.center)
         << "\nradius = " << number_text(s.radius) << '\n';
  }
  std::ofstream out(file);
  out << text.str();
  out.close();
  if (!out) {
    throw std::runtime_error("cannot write '" + file.string() + "': " + std::strerror(errno));
  }
}

}  // namespace grip::grippers
