#include "solver/parallel/step_contacts.hpp"

#include <Eigen/Core>

namespace grip::solver::parallel {

FrictionContacts friction_contacts(const std::vector<int>& vertex,
                                   const std::vector<double>& tangent,
                                   const std::vector<double>& mu_lambda,
                                   const std::vector<int>& contact_begin,
                                   const std::vector<int>& vertex_begin,
                                   const std::vector<double>& eps) {
  FrictionContacts contacts;
  for (std::size_t e = 0; e < eps.size(); ++e) {
    contacts.begin_environment(vertex_begin[e + 1] - vertex_begin[e], eps[e]);
    for (int k = contact_begin[e]; k < contact_begin[e + 1]; ++k) {
      int local[4];
      for (int i = 0; i < 4; ++i) local[i] = vertex[4 * std::size_t(k) + i] - vertex_begin[e];
      contacts.add(local,
                   Eigen::Map<const Eigen::Matrix<double, 12, 2>>(&tangent[24 * std::size_t(k)]),
                   mu_lambda[k]);
    }
  }
  return contacts;
}

FrictionContacts chosen_friction(const FrictionContacts& kept, const FrictionContacts& fresh,
                                 const std::vector<unsigned char>& take) {
  FrictionContacts contacts;
  for (std::size_t e = 0; e < take.size(); ++e) {
    const FrictionContacts& from = take[e] != 0 ? fresh : kept;
    const int first_vertex = from.vertex_begin()[e];
    contacts.begin_environment(from.vertex_begin()[e + 1] - first_vertex, from.eps()[e]);
    for (int k = from.contact_begin()[e]; k < from.contact_begin()[e + 1]; ++k) {
      int local[4];
      for (int i = 0; i < 4; ++i) local[i] = from.vertex()[4 * std::size_t(k) + i] - first_vertex;
      contacts.add(
          local,
          Eigen::Map<const Eigen::Matrix<double, 12, 2>>(&from.tangent()[24 * std::size_t(k)]),
          from.mu_lambda()[k]);
    }
  }
  return contacts;
}

}  // namespace grip::solver::parallel
