#pragma once
// Small jobs for the farm's tests: rigid cylinders and one coarse soft capsule grasped by the
// rigid parallel-jaw gripper (or by two at once), few frames and D1/D2 samples, so a whole run
// takes seconds; and the record-by-record comparison of two datasets.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "io/dataset_reader.hpp"
#include "src/trial/same_result.hpp"

namespace grip::farm::testing {

inline std::string small_job(int cylinders, int candidates, bool soft_object) {
  std::string text =
      "[job]\nname = \"small\"\nseed = 4\n\n[[objects]]\ncategory = \"cylinder\"\ncount = " +
      std::to_string(cylinders) + "\n";
  if (soft_object) {
    text += "\n[[objects]]\ncategory = \"capsule\"\nsoft = true\ntet_edge = 0.012\n";
  }
  text += "\n[[grippers]]\nname = \"parallel-jaw\"\ncandidates = " + std::to_string(candidates) +
          "\n\n[randomization]\nscale = [0.5, 0.6]  # every shape fits the 85 mm jaws\n"
          "\n[trial]\nmetric_samples = 2000\n\n[outputs]\nclosing_frames = 4\n"
          "validation_frames = 6\n";
  return text;
}

// One rigid cylinder held by two parallel-jaw grippers at once: `candidates` bimanual candidates.
inline std::string bimanual_job(int candidates) {
  return "[job]\nname = \"bimanual\"\nseed = 4\n\n[[objects]]\ncategory = \"cylinder\"\n"
         "\n[[grippers]]\nname = \"parallel-jaw\"\nbimanual = true\ncandidates = " +
         std::to_string(candidates) +
         "\n\n[randomization]\nscale = [0.5, 0.6]\n"
         "\n[trial]\nmetric_samples = 2000\n\n[outputs]\nclosing_frames = 4\n"
         "validation_frames = 6\n";
}

// A soft cylinder (1,686 tets, about 1,300 DOFs with both grippers) held by two parallel-jaw
// grippers at once; `farm` is a [farm] table to append (empty: none).
inline std::string bimanual_soft_job(int candidates, const std::string& farm) {
  return "[job]\nname = \"bimanual-soft\"\nseed = 4\n\n[[objects]]\ncategory = \"cylinder\"\n"
         "soft = true\ntet_edge = 0.01\n\n[[grippers]]\nname = \"parallel-jaw\"\n"
         "bimanual = true\ncandidates = " +
         std::to_string(candidates) +
         "\n\n[randomization]\nscale = [0.5, 0.6]\n"
         "\n[trial]\nmetric_samples = 2000\n\n[outputs]\nclosing_frames = 4\n"
         "validation_frames = 6\n" +
         (farm.empty() ? "" : "\n[farm]\n" + farm);
}

inline void write_file(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path) << text;
}

// Every committed record equal bit for bit (wall time aside: the one column that may
// differ), with the same trajectories and stresses.
inline void expect_same_dataset(const std::filesystem::path& a, const std::filesystem::path& b) {
  const io::DatasetReader ra(a), rb(b);
  EXPECT_EQ(ra.job_id(), rb.job_id());
  const std::vector<io::CandidateRecord> ca = ra.candidates(), cb = rb.candidates();
  ASSERT_EQ(ca.size(), cb.size());
  EXPECT_EQ(ra.done(), rb.done());
  for (std::size_t i = 0; i < ca.size(); ++i) {
    EXPECT_TRUE(trial::same_result({ca[i], ra.trajectory(i), ra.stress(i), ra.finger_stress(i)},
                                   {cb[i], rb.trajectory(i), rb.stress(i), rb.finger_stress(i)}))
        << "candidate " << i << " differs between " << a << " and " << b;
  }
}

}  // namespace grip::farm::testing
