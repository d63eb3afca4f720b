#include "farm/petsc/petsc_system_solver.hpp"

#include <petscksp.h>

#include <algorithm>
#include <numeric>
#include <stdexcept>
#include <type_traits>
#include <vector>

#include "farm/petsc/row_partition.hpp"

namespace grip::farm {

namespace {

// What rank 0 asks the serving ranks to do next.
enum Command : int { kStop = 0, kFactorize = 1, kSolve = 2 };

void check(PetscErrorCode error, const char* call) {
  if (error != 0) throw std::runtime_error(std::string("PETSc: ") + call + " failed");
}

// Counts and displacements of a scatter of rows [begin[r], begin[r + 1]) to each rank r.
struct Layout {
  std::vector<int> counts;
  std::vector<int> offsets;
};

Layout layout_of(const std::vector<int>& begin) {
  Layout layout;
  for (std::size_t r = 0; r + 1 < begin.size(); ++r) {
    layout.offsets.push_back(begin[r]);
    layout.counts.push_back(begin[r + 1] - begin[r]);
  }
  return layout;
}

}  // namespace

struct PetscSystemSolver::Impl {
  MPI_Comm comm = MPI_COMM_NULL;  // our own duplicate: commands never meet the caller's messages
  int rank = 0;
  int ranks = 1;
  std::string prefix;
  KSP ksp = nullptr;
  Mat matrix = nullptr;
  Vec rhs = nullptr;
  Vec solution = nullptr;
  bool stopped = false;
  std::string failure;
  int iterations = 0;
  std::uint64_t solves = 0;

  // Every rank: the global size, the new rows each rank owns, and this rank's rows (CSR,
  // global new column numbers).
  int n = 0;
  std::vector<int> row_begin;
  std::vector<PetscInt> local_row_start;
  std::vector<PetscInt> local_columns;
  std::vector<PetscScalar> local_values;

  // Rank 0: the pattern last distributed, its partition, the whole matrix in new numbering
  // (CSR, both triangles) with the lower-triangle value each entry takes, and the entries'
  // split among ranks.
  std::vector<int> outer;
  std::vector<int> inner;
  RowPartition partition;
  std::vector<int> row_start;
  std::vector<int> columns;
  std::vector<int> source;
  std::vector<double> values;
  Layout row_layout;
  Layout entry_layout;
  std::vector<double> buffer;  // a vector in new numbering

  bool same_pattern(const Eigen::SparseMatrix<double>& m) const {
    return matrix != nullptr && m.outerSize() + 1 == static_cast<Eigen::Index>(outer.size()) &&
           std::equal(outer.begin(), outer.end(), m.outerIndexPtr()) &&
           std::equal(inner.begin(), inner.end(), m.innerIndexPtr());
  }

  // Rank 0: renumbers a new pattern (partitioning anew only when the size changed: a contact
  // that comes or goes leaves the partition valid) and lays out the whole matrix's CSR.
  void lay_out(const Eigen::SparseMatrix<double>& lower) {
    const int size = static_cast<int>(lower.rows());
    if (size != n || partition.new_of_old.empty()) {
      partition = partition_rows(lower, ranks, size % 3 == 0 ? 3 : 1);
    }
    n = size;
    row_begin = partition.row_begin;
    const std::vector<int>& renumber = partition.new_of_old;
    row_start.assign(n + 1, 0);
    for (int c = 0; c < n; ++c) {
      for (int k = lower.outerIndexPtr()[c]; k < lower.outerIndexPtr()[c + 1]; ++k) {
        const int r = lower.innerIndexPtr()[k];
        ++row_start[renumber[r] + 1];
        if (r != c) ++row_start[renumber[c] + 1];
      }
    }
    std::partial_sum(row_start.begin(), row_start.end(), row_start.begin());
    columns.resize(row_start[n]);
    source.resize(row_start[n]);
    std::vector<int> next(row_start.begin(), row_start.end() - 1);
    for (int c = 0; c < n; ++c) {
      for (int k = lower.outerIndexPtr()[c]; k < lower.outerIndexPtr()[c + 1]; ++k) {
        const int r = lower.innerIndexPtr()[k];
        const int a = renumber[r], b = renumber[c];
        columns[next[a]] = b;
        source[next[a]++] = k;
        if (r != c) {
          columns[next[b]] = a;
          source[next[b]++] = k;
        }
      }
    }
    // PETSc wants each row's columns in order.
    std::vector<std::pair<int, int>> row;
    for (int i = 0; i < n; ++i) {
      row.clear();
      for (int e = row_start[i]; e < row_start[i + 1]; ++e) row.emplace_back(columns[e], source[e]);
      std::sort(row.begin(), row.end());
      for (std::size_t j = 0; j < row.size(); ++j) {
        columns[row_start[i] + j] = row[j].first;
        source[row_start[i] + j] = row[j].second;
      }
    }
    row_layout = layout_of(row_begin);
    std::vector<int> entry_begin;
    for (const int r : row_begin) entry_begin.push_back(row_start[r]);
    entry_layout = layout_of(entry_begin);
    outer.assign(lower.outerIndexPtr(), lower.outerIndexPtr() + lower.outerSize() + 1);
    inner.assign(lower.innerIndexPtr(), lower.innerIndexPtr() + lower.nonZeros());
  }

  // Every rank: receives its rows (the pattern too when it is new) and assembles the matrix,
  // then sets the preconditioner up. The same verdict on every rank.
  bool distribute_and_set_up(const Eigen::SparseMatrix<double>* lower) {
    int new_pattern = rank == 0 ? !same_pattern(*lower) : 0;
    const int previous_n = n;
    if (rank == 0 && new_pattern) lay_out(*lower);
    MPI_Bcast(&new_pattern, 1, MPI_INT, 0, comm);
    if (new_pattern) {
      MPI_Bcast(&n, 1, MPI_INT, 0, comm);
      row_begin.resize(ranks + 1);
      MPI_Bcast(row_begin.data(), ranks + 1, MPI_INT, 0, comm);
      const int local_rows = row_begin[rank + 1] - row_begin[rank];
      std::vector<int> row_lengths;
      if (rank == 0) {
        row_lengths.resize(n);
        for (int i = 0; i < n; ++i) row_lengths[i] = row_start[i + 1] - row_start[i];
      }
      std::vector<int> local_lengths(local_rows);
      MPI_Scatterv(row_lengths.data(), row_layout.counts.data(), row_layout.offsets.data(), MPI_INT,
                   local_lengths.data(), local_rows, MPI_INT, 0, comm);
      local_row_start.assign(local_rows + 1, 0);
      for (int i = 0; i < local_rows; ++i) {
        local_row_start[i + 1] = local_row_start[i] + local_lengths[i];
      }
      local_columns.resize(local_row_start[local_rows]);
      local_values.resize(local_row_start[local_rows]);
      std::vector<int> received(local_columns.size());
      MPI_Scatterv(columns.data(), entry_layout.counts.data(), entry_layout.offsets.data(), MPI_INT,
                   received.data(), static_cast<int>(received.size()), MPI_INT, 0, comm);
      std::copy(received.begin(), received.end(), local_columns.begin());
    }
    if (rank == 0) {
      values.resize(source.size());
      for (std::size_t e = 0; e < source.size(); ++e) values[e] = lower->valuePtr()[source[e]];
    }
    static_assert(std::is_same_v<PetscScalar, double>, "grip's PETSc must be real, double");
    MPI_Scatterv(values.data(), entry_layout.counts.data(), entry_layout.offsets.data(), MPI_DOUBLE,
                 local_values.data(), static_cast<int>(local_values.size()), MPI_DOUBLE, 0, comm);
    // A KSP keeps its preconditioner's sizes (multigrid its levels'): another size, another KSP.
    if (new_pattern && matrix != nullptr && n != previous_n) {
      check(KSPDestroy(&ksp), "KSPDestroy");
      create_ksp();
    }
    new_pattern ? create_matrix() : update_matrix();
    check(KSPSetOperators(ksp, matrix, matrix), "KSPSetOperators");
    if (KSPSetUp(ksp) != 0) {
      failure = "PETSc could not set up " + method();
      return false;
    }
    // The blocks' factorizations too, so that a failed one fails factorize().
    check(KSPSetUpOnBlocks(ksp), "KSPSetUpOnBlocks");
    PCFailedReason pc_reason = PC_NOERROR;
    PC pc = nullptr;
    check(KSPGetPC(ksp, &pc), "KSPGetPC");
    check(PCGetFailedReasonRank(pc, &pc_reason), "PCGetFailedReasonRank");
    int failed = pc_reason != PC_NOERROR, any_failed = 0;
    MPI_Allreduce(&failed, &any_failed, 1, MPI_INT, MPI_MAX, comm);
    if (any_failed) {
      failure = "the preconditioner of " + method() + " failed: " + PCFailedReasons[pc_reason];
      return false;
    }
    return true;
  }

  // A KSP configured by the options database under our prefix, grip's defaults filled in.
  void create_ksp() {
    for (const auto& [name, value] : default_options()) {
      PetscBool given = PETSC_FALSE;
      check(PetscOptionsHasName(nullptr, prefix.c_str(), ("-" + name).c_str(), &given), "options");
      if (!given) {
        check(PetscOptionsSetValue(nullptr, ("-" + prefix + name).c_str(), value.c_str()),
              "PetscOptionsSetValue");
      }
    }
    check(KSPCreate(comm, &ksp), "KSPCreate");
    if (!prefix.empty()) {
      check(KSPSetOptionsPrefix(ksp, prefix.c_str()), "KSPSetOptionsPrefix");
    }
    check(KSPSetFromOptions(ksp), "KSPSetFromOptions");
    // CG measures the true residual at no extra cost; other KSPs keep their own default norm.
    PetscBool cg = PETSC_FALSE, norm_given = PETSC_FALSE;
    check(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(ksp), KSPCG, &cg), "type");
    check(PetscOptionsHasName(nullptr, prefix.c_str(), "-ksp_norm_type", &norm_given), "options");
    if (cg && !norm_given) {
      check(KSPSetNormType(ksp, KSP_NORM_UNPRECONDITIONED), "KSPSetNormType");
    }
  }

  void create_matrix() {
    check(MatDestroy(&matrix), "MatDestroy");
    check(VecDestroy(&rhs), "VecDestroy");
    check(VecDestroy(&solution), "VecDestroy");
    const PetscInt local_rows = row_begin[rank + 1] - row_begin[rank];
    check(MatCreate(comm, &matrix), "MatCreate");
    check(MatSetSizes(matrix, local_rows, local_rows, n, n), "MatSetSizes");
    // 3x3 vertex blocks (METIS never splits one): GAMG aggregates and smooths by them.
    check(MatSetBlockSize(matrix, n % 3 == 0 ? 3 : 1), "MatSetBlockSize");
    check(MatSetType(matrix, MATAIJ), "MatSetType");
    check(MatSeqAIJSetPreallocationCSR(matrix, local_row_start.data(), local_columns.data(),
                                       local_values.data()),
          "MatSeqAIJSetPreallocationCSR");
    check(MatMPIAIJSetPreallocationCSR(matrix, local_row_start.data(), local_columns.data(),
                                       local_values.data()),
          "MatMPIAIJSetPreallocationCSR");
    check(MatSetOption(matrix, MAT_SPD, PETSC_TRUE), "MatSetOption");
    check(MatSetOption(matrix, MAT_SYMMETRY_ETERNAL, PETSC_TRUE), "MatSetOption");
    check(MatCreateVecs(matrix, &solution, &rhs), "MatCreateVecs");
  }

  void update_matrix() {
    const PetscInt first = row_begin[rank];
    for (std::size_t i = 0; i + 1 < local_row_start.size(); ++i) {
      const PetscInt row = first + static_cast<PetscInt>(i);
      const PetscInt begin = local_row_start[i];
      check(MatSetValues(matrix, 1, &row, local_row_start[i + 1] - begin,
                         local_columns.data() + begin, local_values.data() + begin, INSERT_VALUES),
            "MatSetValues");
    }
    check(MatAssemblyBegin(matrix, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
    check(MatAssemblyEnd(matrix, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
  }

  // Every rank: runs the KSP on rank 0's right-hand side and returns the solution to rank 0.
  bool solve(const Eigen::VectorXd* b, Eigen::VectorXd* x) {
    if (rank == 0) {
      buffer.resize(n);
      for (int i = 0; i < n; ++i) buffer[partition.new_of_old[i]] = (*b)[i];
    }
    PetscScalar* local = nullptr;
    PetscInt local_size = 0;
    check(VecGetLocalSize(rhs, &local_size), "VecGetLocalSize");
    check(VecGetArray(rhs, &local), "VecGetArray");
    MPI_Scatterv(buffer.data(), row_layout.counts.data(), row_layout.offsets.data(), MPI_DOUBLE,
                 local, static_cast<int>(local_size), MPI_DOUBLE, 0, comm);
    check(VecRestoreArray(rhs, &local), "VecRestoreArray");
    check(KSPSolve(ksp, rhs, solution), "KSPSolve");
    KSPConvergedReason reason = KSP_CONVERGED_ITERATING;
    PetscInt its = 0;
    check(KSPGetConvergedReason(ksp, &reason), "KSPGetConvergedReason");
    check(KSPGetIterationNumber(ksp, &its), "KSPGetIterationNumber");
    iterations = static_cast<int>(its);
    const PetscScalar* result = nullptr;
    check(VecGetArrayRead(solution, &result), "VecGetArrayRead");
    MPI_Gatherv(result, static_cast<int>(local_size), MPI_DOUBLE, buffer.data(),
                row_layout.counts.data(), row_layout.offsets.data(), MPI_DOUBLE, 0, comm);
    check(VecRestoreArrayRead(solution, &result), "VecRestoreArrayRead");
    if (reason <= 0) {
      failure = method() + " did not converge: " + KSPConvergedReasons[reason] + " after " +
                std::to_string(iterations) + " iterations";
      return false;
    }
    if (rank == 0) {
      x->resize(n);
      for (int i = 0; i < n; ++i) (*x)[i] = buffer[partition.new_of_old[i]];
    }
    return true;
  }

  // "ksp + pc", with the blocks' or levels' preconditioner where the PC has them.
  std::string method() const {
    KSPType ksp_type = nullptr;
    PCType pc_type = nullptr;
    PC pc = nullptr;
    KSPGetType(ksp, &ksp_type);
    KSPGetPC(ksp, &pc);
    PCGetType(pc, &pc_type);
    const std::string pc_name = pc_type ? pc_type : "?";
    std::string name = std::string(ksp_type ? ksp_type : "?") + " + " + pc_name;
    const char* inner = pc_name == PCBJACOBI || pc_name == PCASM ? "-sub_pc_type"
                        : pc_name == PCGAMG || pc_name == PCMG   ? "-mg_levels_pc_type"
                                                                 : nullptr;
    char inner_type[64] = "";
    PetscBool given = PETSC_FALSE;
    if (inner != nullptr) {
      PetscOptionsGetString(nullptr, prefix.c_str(), inner, inner_type, sizeof(inner_type), &given);
    }
    return given ? name + "/" + inner_type : name;
  }

  void free_petsc() {
    MatDestroy(&matrix);
    VecDestroy(&rhs);
    VecDestroy(&solution);
    KSPDestroy(&ksp);
    MPI_Comm_free(&comm);
    stopped = true;
  }
};

const std::vector<std::pair<std::string, std::string>>& PetscSystemSolver::default_options() {
  static const std::vector<std::pair<std::string, std::string>> defaults = {
      {"ksp_type", "cg"},
      {"pc_type", "gamg"},
      {"mg_levels_ksp_type", "richardson"},
      {"mg_levels_pc_type", "sor"},
      {"sub_pc_type", "icc"},  // the blocks of bjacobi or asm, when
                               // chosen instead
      {"ksp_rtol", "1e-10"},
      {"ksp_max_it", "10000"}};
  return defaults;
}

PetscSystemSolver::PetscSystemSolver(MPI_Comm comm, const std::string& options_prefix)
    : impl_(std::make_unique<Impl>()) {
  Impl& impl = *impl_;
  MPI_Comm_dup(comm, &impl.comm);
  MPI_Comm_rank(impl.comm, &impl.rank);
  MPI_Comm_size(impl.comm, &impl.ranks);
  impl.prefix = options_prefix;
  impl.create_ksp();
}

PetscSystemSolver::~PetscSystemSolver() {
  if (impl_ && !impl_->stopped) {
    if (impl_->rank == 0) {
      stop();
    } else {
      impl_->free_petsc();  // serve() was never run: rank 0 stopped no one
    }
  }
}

bool PetscSystemSolver::factorize(const Eigen::SparseMatrix<double>& lower) {
  Impl& impl = *impl_;
  if (impl.rank != 0 || impl.stopped) {
    throw std::logic_error("PetscSystemSolver::factorize is rank 0's, before stop()");
  }
  if (!lower.isCompressed() || lower.rows() != lower.cols()) {
    throw std::invalid_argument("PetscSystemSolver::factorize needs a compressed square matrix");
  }
  int command = kFactorize;
  MPI_Bcast(&command, 1, MPI_INT, 0, impl.comm);
  return impl.distribute_and_set_up(&lower);
}

bool PetscSystemSolver::solve(const Eigen::VectorXd& rhs, Eigen::VectorXd& x) {
  Impl& impl = *impl_;
  if (impl.rank != 0 || impl.stopped || impl.matrix == nullptr) {
    throw std::logic_error("PetscSystemSolver::solve is rank 0's, after factorize()");
  }
  if (rhs.size() != impl.n) {
    throw std::invalid_argument("PetscSystemSolver::solve: right-hand side of size " +
                                std::to_string(rhs.size()) + " for " + std::to_string(impl.n) +
                                " rows");
  }
  int command = kSolve;
  MPI_Bcast(&command, 1, MPI_INT, 0, impl.comm);
  ++impl.solves;
  return impl.solve(&rhs, &x);
}

std::string PetscSystemSolver::failure() const { return impl_->failure; }

void PetscSystemSolver::serve() {
  Impl& impl = *impl_;
  if (impl.rank == 0) throw std::logic_error("PetscSystemSolver::serve is for ranks other than 0");
  while (!impl.stopped) {
    int command = kStop;
    MPI_Bcast(&command, 1, MPI_INT, 0, impl.comm);
    switch (command) {
      case kFactorize:
        impl.distribute_and_set_up(nullptr);
        break;
      case kSolve:
        impl.solve(nullptr, nullptr);
        break;
      default:
        impl.free_petsc();
    }
  }
}

void PetscSystemSolver::stop() {
  Impl& impl = *impl_;
  if (impl.rank != 0) throw std::logic_error("PetscSystemSolver::stop is rank 0's");
  if (impl.stopped) return;
  int command = kStop;
  MPI_Bcast(&command, 1, MPI_INT, 0, impl.comm);
  impl.free_petsc();
}

int PetscSystemSolver::rank() const { return impl_->rank; }
int PetscSystemSolver::ranks() const { return impl_->ranks; }
int PetscSystemSolver::iterations() const { return impl_->iterations; }
std::uint64_t PetscSystemSolver::solves() const { return impl_->solves; }
std::string PetscSystemSolver::method() const { return impl_->method(); }

}  // namespace grip::farm
