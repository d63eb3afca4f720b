#pragma once
// The one exception type of the dataset layer: a message meant for a person, naming the file,
// what is wrong and what to do about it.
#include <stdexcept>

namespace grip::io {

class DatasetError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace grip::io
