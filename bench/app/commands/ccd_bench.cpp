// `grip ccd-bench --type vf|ee FILE.csv`: additive CCD scored on a file of the CCD benchmark
// (Wang et al. 2021) rational CSV format; `grip ccd-bench --write-hard DIR` writes the generated
// hard query set in that format. A query whose exact primitives touch at t = 0 counts as a
// collision, whatever its label. The last line of a scoring run is one JSON object.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "app/cli/command_line.hpp"
#include "bench/app/commands.hpp"
#include "bench/ccd/ccd_benchmark.hpp"
#include "bench/ccd/ccd_query_file.hpp"
#include "bench/ccd/hard_ccd_queries.hpp"

namespace grip::commands {

namespace {

struct CcdBenchArgs {
  std::string file;            // rational CSV query file (Wang et al. 2021 format)
  std::string type;            // "vf" (vertex-face) or "ee" (edge-edge)
  std::string write_hard_dir;  // if set: write hard-vertex-face.csv and hard-edge-edge.csv here
};

int write_hard_queries(const std::filesystem::path& dir) {
  std::filesystem::create_directories(dir);
  for (const auto type : {bench::CcdQueryType::kVertexFace, bench::CcdQueryType::kEdgeEdge}) {
    const auto path = dir / (type == bench::CcdQueryType::kVertexFace ? "hard-vertex-face.csv"
                                                                      : "hard-edge-edge.csv");
    const auto queries = bench::hard_ccd_queries(type);
    bench::write_ccd_query_file(path, queries);
    std::printf("wrote %zu queries to %s\n", queries.size(), path.string().c_str());
  }
  return 0;
}

int ccd_bench(const CcdBenchArgs& args) {
  if (!args.write_hard_dir.empty()) return write_hard_queries(args.write_hard_dir);
  if (args.file.empty() || args.type.empty()) {
    std::fprintf(stderr,
                 "grip ccd-bench: give a query file and its type (grip ccd-bench --type vf|ee "
                 "FILE.csv), or --write-hard DIR; see 'grip ccd-bench --help'\n");
    return 2;
  }
  const bench::CcdQueryType type =
      args.type == "vf" ? bench::CcdQueryType::kVertexFace : bench::CcdQueryType::kEdgeEdge;
  const std::vector<bench::CcdQuery> queries = bench::read_ccd_query_file(args.file, type);
  std::size_t touching_labelled_apart = 0;
  for (const bench::CcdQuery& q : queries)
    touching_labelled_apart += q.touches_at_start && !q.collides;

  // Minimum separation 0: the benchmark's truth is about touching, not about a gap.
  const solver::kernels::AccdOptions options;
  const bench::CcdBenchmarkResult r = bench::run_ccd_benchmark(queries, type, options);
  const std::size_t misses = queries.size() - r.collisions;
  std::printf(
      "%s: %zu %s queries (%zu collide, %zu of them touching at t = 0, which counts as a "
      "collision; %zu do not); ACCD s = %g, min separation %g\n",
      args.file.c_str(), r.queries, args.type.c_str(), r.collisions, r.touching_starts, misses,
      options.rescaling, options.min_separation);
  if (touching_labelled_apart > 0) {
    std::printf("%zu touching starts are labelled 0 in the file and scored as collisions\n",
                touching_labelled_apart);
  }
  std::printf(
      "false positives %zu (%.1f%% of the non-colliding), false negatives %zu (%zu at touching "
      "starts), unsafe times of impact %zu, most iterations %zu\n",
      r.false_positives,
      misses ? 100.0 * static_cast<double>(r.false_positives) / static_cast<double>(misses) : 0.0,
      r.false_negatives, r.touching_start_false_negatives, r.unsafe_times, r.max_iterations);
  std::printf("%s\n", bench::summary_json(r).c_str());
  std::fflush(stdout);
  return 0;
}

}  // namespace

void declare_ccd_bench(cli::Command& root) {
  auto args = std::make_shared<CcdBenchArgs>();
  cli::Command ccd = root.subcommand(
      "ccd-bench", "Score additive CCD on a CCD benchmark file (Wang et al. 2021 rational CSV)");
  cli::Option file = ccd.option("file", args->file, "Query file (8 rows per query)");
  cli::Option type =
      ccd.option("--type", args->type, "Query type: vf (vertex-face), ee (edge-edge)")
          .check(cli::Check::one_of({"vf", "ee"}));
  cli::Option write = ccd.option(
      "--write-hard", args->write_hard_dir,
      "Write the generated hard query set (hard-vertex-face.csv, hard-edge-edge.csv) to DIR");
  write.check(cli::Check::output_folder());
  file.needs(type);
  write.excludes(file).excludes(type);
  ccd.on_run([args] { return ccd_bench(*args); });
}

}  // namespace grip::commands
