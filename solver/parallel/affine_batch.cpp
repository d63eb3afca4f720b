#include "solver/parallel/affine_batch.hpp"

#include <stdexcept>
#include <string>

namespace grip::solver::parallel {

void AffineBatch::begin_environment(int dof_count) {
  dof_begin_.push_back(dof_begin_.back() + dof_count);
  body_begin_.push_back(body_begin_.back());
}

void AffineBatch::add_body(int first_dof, const AffineBodyValues& body) {
  if (environment_count() == 0) {
    throw std::logic_error("AffineBatch::add_body before begin_environment");
  }
  const int environment = environment_count() - 1;
  const std::string name = "AffineBatch: body " + std::to_string(dof_.size());
  if (!body.mass_matrix || !body.mass_matrix_inverse || !(body.mass_matrix[0] > 0.0)) {
    throw std::invalid_argument(name + " has no mass matrix");
  }
  if (!(body.volume > 0.0) || !(body.density > 0.0) || !(body.orthogonality_stiffness > 0.0)) {
    throw std::invalid_argument(name + " needs a positive volume, density and stiffness");
  }
  if (!(body.drive_stiffness >= 0.0)) {
    throw std::invalid_argument(name + " has a negative drive stiffness");
  }
  const int dof = dof_begin_[static_cast<std::size_t>(environment)] + first_dof;
  if (first_dof < 0 || dof + 12 > dof_begin_.back()) {
    throw std::invalid_argument(name + "'s DOFs lie outside its environment");
  }
  dof_.push_back(dof);
  environment_.push_back(environment);
  mass_matrix_.insert(mass_matrix_.end(), body.mass_matrix, body.mass_matrix + 144);
  mass_matrix_inverse_.insert(mass_matrix_inverse_.end(), body.mass_matrix_inverse,
                              body.mass_matrix_inverse + 144);
  weight_mass_.push_back(body.falls ? body.density * body.volume : 0.0);
  volume_.push_back(body.volume);
  orthogonality_stiffness_.push_back(body.orthogonality_stiffness);
  drive_stiffness_.push_back(body.drive_stiffness);
  body_begin_.back() = static_cast<int>(dof_.size());
}

AffineBuffers AffineBatch::bodies() const {
  return {static_cast<int>(dof_.size()),
          dof_.data(),
          environment_.data(),
          mass_matrix_.data(),
          mass_matrix_inverse_.data(),
          weight_mass_.data(),
          volume_.data(),
          orthogonality_stiffness_.data(),
          drive_stiffness_.data()};
}

}  // namespace grip::solver::parallel
