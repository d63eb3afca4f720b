#pragma once
// What both engines keep on the host (solver/engine/engine.hpp): one Environment per
// environment of the batch, and which of them are retired. The CPU engine (Batch) steps them;
// the data-parallel engine (ParallelEngine) steps their states in its buffers and keeps them as
// its host handles.
#include <memory>
#include <vector>

#include "solver/engine/engine.hpp"
#include "solver/environment.hpp"

namespace grip::solver {

class HostEnvironments : public Engine {
 public:
  // Adds an environment of `model` and returns its index. Take it with environment(i) to place
  // bodies, set gravity and scripts between steps.
  int add(std::shared_ptr<const Model> model) override;
  Environment& environment(int index) override {
    return *environments_.at(static_cast<std::size_t>(index));
  }
  const Environment& environment(int index) const override {
    return *environments_.at(static_cast<std::size_t>(index));
  }
  int size() const override { return static_cast<int>(environments_.size()); }

  // Takes an environment out of further steps (its trial is over); it keeps its state.
  void retire(int index) override { active_.at(static_cast<std::size_t>(index)) = 0; }
  // Not retired and not failed.
  bool active(int index) const override;
  bool any_active() const override;

 private:
  std::vector<std::unique_ptr<Environment>> environments_;
  std::vector<char> active_;
};

}  // namespace grip::solver
