// The result benchmarks as a user runs them from a fresh build: `grip bench hard` writes its
// table, CSV and plot and exits 0 when every case holds; an unknown case, a bimanual accuracy
// scene (there is none) or an unknown sweep is one message and exit status 1; `grip bench
// labels` refuses an arm without its object model or an unknown category in one line, exit 2,
// writing nothing, `grip bench trial` an unknown gripper or no repeats, and `grip bench cost` an
// unknown gripper or no reference repeats; `grip bench peer` refuses an unknown category (and
// --mujoco-ipc but for the fin-ray) the same way, and writes its files and JSON line, for the
// jaws and for the hand (or, built without MuJoCo, says how to install it in one line, exit 1);
// `grip bench scale` predicts from a cost file and refuses an unknown what-if or a class without
// costs in one line, exit 2.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "tests/app/run_grip.hpp"

namespace {

namespace fs = std::filesystem;
using grip::testing::run_grip;
using grip::testing::slurp;

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("grip_bench_cli_" + name);
  fs::remove_all(dir);
  return dir;
}

TEST(BenchCli, HardWritesItsTablesAndPasses) {
  const fs::path out = scratch("hard");
  const auto run = run_grip(
      "bench hard --cases mu_3.5_incline,parallel_edge_edge --threads 1 --out " + out.string());
  EXPECT_EQ(run.exit_code, 0) << run.out << run.err;
  EXPECT_NE(run.out.find("all cases pass"), std::string::npos) << run.out;
  const std::string csv = slurp(out / "hard.csv");
  EXPECT_NE(csv.find("mu_3.5_incline"), std::string::npos) << csv;
  EXPECT_NE(csv.find("parallel_edge_edge"), std::string::npos) << csv;
  EXPECT_EQ(csv.find("large_squeeze"), std::string::npos) << "only the cases asked for";
  EXPECT_TRUE(fs::exists(out / "hard.md"));
  fs::remove_all(out);
}

TEST(BenchCli, UnknownNamesAreOneMessageAndExitOne) {
  const fs::path out = scratch("bad");
  const auto hard = run_grip("bench hard --cases no_such_case --out " + out.string());
  EXPECT_EQ(hard.exit_code, 1);
  EXPECT_NE((hard.out + hard.err).find("no_such_case"), std::string::npos) << hard.err;
  const auto bimanual = run_grip("bench accuracy --scenes bimanual --out " + out.string());
  EXPECT_EQ(bimanual.exit_code, 1);
  EXPECT_NE((bimanual.out + bimanual.err).find("bimanual"), std::string::npos) << bimanual.err;
  const auto sweep = run_grip("bench accuracy --sweeps no_such_setting --out " + out.string());
  EXPECT_EQ(sweep.exit_code, 1);
  EXPECT_NE((sweep.out + sweep.err).find("no_such_setting"), std::string::npos) << sweep.err;
  fs::remove_all(out);
}

TEST(BenchCli, LabelsRefusesBadArmsAndCategoriesInOneLine) {
  const fs::path out = scratch("labels");
  const auto arm = run_grip("bench labels --arms fin-ray --out " + out.string());
  EXPECT_EQ(arm.exit_code, 2);
  EXPECT_NE(arm.err.find("--arms 'fin-ray': write gripper:rigid or gripper:soft"),
            std::string::npos)
      << arm.err;
  const auto category = run_grip("bench labels --categories teacup --out " + out.string());
  EXPECT_EQ(category.exit_code, 2);
  EXPECT_NE(category.err.find("teacup"), std::string::npos) << category.err;
  EXPECT_FALSE(fs::exists(out));
}

TEST(BenchCli, TrialRefusesAnUnknownGripperAndNoRepeatsInOneLine) {
  const fs::path out = scratch("trial");
  const auto gripper = run_grip("bench trial --arms gripper-x:rigid --out " + out.string());
  EXPECT_EQ(gripper.exit_code, 2);
  EXPECT_NE(gripper.err.find("grip bench trial: unknown gripper 'gripper-x'"), std::string::npos)
      << gripper.err;
  EXPECT_EQ(gripper.err.find('\n'), gripper.err.size() - 1) << gripper.err;
  const auto repeats = run_grip("bench trial --repeats 0 --out " + out.string());
  EXPECT_EQ(repeats.exit_code, 2);
  EXPECT_NE(repeats.err.find("grip: --repeats: must be a whole number >= 1, not '0'"),
            std::string::npos)
      << repeats.err;
  EXPECT_EQ(repeats.err.find('\n'), repeats.err.size() - 1) << repeats.err;
  EXPECT_FALSE(fs::exists(out));
}

TEST(BenchCli, CostRefusesAnUnknownGripperAndNoReferenceInOneLine) {
  const fs::path out = scratch("cost");
  const auto gripper = run_grip("bench cost --grippers claw --out " + out.string());
  EXPECT_EQ(gripper.exit_code, 2);
  EXPECT_NE(gripper.err.find("--grippers"), std::string::npos) << gripper.err;
  EXPECT_NE(gripper.err.find("parallel-jaw"), std::string::npos) << gripper.err;
  EXPECT_EQ(gripper.err.find('\n'), gripper.err.size() - 1) << gripper.err;
  const auto repeats = run_grip("bench cost --reference-repeats 0 --out " + out.string());
  EXPECT_EQ(repeats.exit_code, 2);
  EXPECT_NE(repeats.err.find("grip: --reference-repeats: must be a whole number >= 1, not '0'"),
            std::string::npos)
      << repeats.err;
  EXPECT_FALSE(fs::exists(out));
}

TEST(BenchCli, PeerRefusesAnUnknownCategoryAndRunsOrNamesMujoco) {
  const fs::path out = scratch("peer");
  const auto category = run_grip("bench peer --categories teacup --out " + out.string());
  EXPECT_EQ(category.exit_code, 2);
  EXPECT_NE(category.err.find("teacup"), std::string::npos) << category.err;
  EXPECT_EQ(category.err.find('\n'), category.err.size() - 1) << category.err;
  EXPECT_FALSE(fs::exists(out));
  const auto ipc = run_grip("bench peer --gripper leap --mujoco-ipc --out " + out.string());
  EXPECT_EQ(ipc.exit_code, 2);
  EXPECT_NE(ipc.err.find("--gripper fin-ray only"), std::string::npos) << ipc.err;
  EXPECT_FALSE(fs::exists(out));
  const auto run =
      run_grip("bench peer --categories box --seeds 1 --candidates 2 --out " + out.string());
  if (run.exit_code == 1) {
    EXPECT_NE(run.err.find("scripts/install-peers.sh"), std::string::npos) << run.err;
    EXPECT_EQ(run.err.find('\n'), run.err.size() - 1) << run.err;
    return;
  }
  EXPECT_EQ(run.exit_code, 0) << run.out << run.err;
  EXPECT_NE(run.out.find("{\"benchmark\": \"peer\""), std::string::npos) << run.out;
  EXPECT_NE(slurp(out / "peer.csv").find("parallel-jaw,box,"), std::string::npos);
  EXPECT_TRUE(fs::exists(out / "peer.md"));
  const std::string leap = "bench peer --gripper leap --categories box --seeds 1 --candidates 1";
  const auto hand = run_grip(leap + " --out " + out.string());
  EXPECT_EQ(hand.exit_code, 0) << hand.out << hand.err;
  EXPECT_NE(slurp(out / "peer-leap.csv").find("leap,box,"), std::string::npos);
  EXPECT_TRUE(fs::exists(out / "peer-leap.md"));
  fs::remove_all(out);
}

TEST(BenchCli, ScalePredictsFromACostFileAndRefusesUnknownWhatIfs) {
  const fs::path out = scratch("scale");
  fs::create_directories(out);
  const fs::path costs = out / "trial.csv";
  std::ofstream(costs) << "arm,settings,wall_s\nfin-ray x rigid,defaults,4\n"
                          "fin-ray x soft,defaults,12\nfin-ray x soft,reference,30\n";
  const std::string common = "bench scale --costs " + costs.string() +
                             " --objects 12 --candidates 120 --ranks 2,4 --out " + out.string();
  const auto run = run_grip(common + " --what-if rounds,round-batches=8+heaviest-first");
  EXPECT_EQ(run.exit_code, 0) << run.out << run.err;
  const std::string csv = slurp(out / "scale.csv");
  EXPECT_NE(csv.find("\nrounds,4,"), std::string::npos) << csv;
  EXPECT_NE(csv.find("\nround-batches=8+heaviest-first,2,"), std::string::npos) << csv;
  EXPECT_NE(run.out.find("{\"trials\": 120"), std::string::npos) << run.out;
  const auto bad = run_grip(common + " --what-if faster");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("'faster' is not one of"), std::string::npos) << bad.err;
  const auto missing = run_grip(common + " --grippers leap");
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.err.find("no measured trial cost for 'leap x"), std::string::npos)
      << missing.err;
  fs::remove_all(out);
}

}  // namespace
