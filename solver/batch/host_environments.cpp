#include "solver/batch/host_environments.hpp"

#include <utility>

namespace grip::solver {

int HostEnvironments::add(std::shared_ptr<const Model> model) {
  environments_.push_back(std::make_unique<Environment>(std::move(model)));
  active_.push_back(1);
  return size() - 1;
}

bool HostEnvironments::active(int index) const {
  return active_.at(static_cast<std::size_t>(index)) && !environment(index).failed();
}

bool HostEnvironments::any_active() const {
  for (int i = 0; i < size(); ++i) {
    if (active(i)) return true;
  }
  return false;
}

}  // namespace grip::solver
