#pragma once
// A soft parallel gripper a user describes in a TOML file (docs/assets.md, "Your own soft
// gripper"): one finger's tet mesh from another tool, its material, the vertices pinned to the
// jaw, the finger's axes in the mesh's frame, the jaws' stroke, and whether the second finger is
// the first turned half a turn about the approach axis (as the built-in grippers') or its
// mirror image.
#include <filesystem>

#include "src/grippers/parallel_gripper.hpp"

namespace grip::grippers {

// The largest finger a description may hold, across (m): a finger meshed in millimetres and
// read as metres is refused by it.
inline constexpr double kMaxDescribedFingerSize = 1.0;
// The smallest (m): a finger this small would be a scale mistake, and its tets degenerate.
inline constexpr double kMinDescribedFingerSize = 1e-3;

// Reads `file` and builds the gripper: its name is the file's [gripper] name, its finger the
// mesh turned into the finger frame of FinRayOptions (contact face on y = 0 facing -y, the
// mount at z = 0, x centred). Throws config::ConfigError ("FILE:LINE: ...") for a key that is
// missing, misspelt or out of range, and for a mesh that cannot be simulated (inverted or
// degenerate tets, a boundary that is not a closed manifold, a finger larger than
// kMaxDescribedFingerSize, a mount that pins fewer than three vertices off one line), naming
// the key and the fix.
ParallelGripper load_gripper_description(const std::filesystem::path& file);

// True when `text` (a --gripper value or a job's description key) names a description file
// rather than a built-in gripper: it ends in ".toml".
bool is_gripper_description(const std::filesystem::path& text);

}  // namespace grip::grippers
