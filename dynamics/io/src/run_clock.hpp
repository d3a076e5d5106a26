#pragma once
// The wall time of a run (scene_output.cpp, scene3d_output.cpp, scene_cdem_output.cpp), split
// into the time spent writing files and the rest, the simulation's. Internal to the io module.

#include <chrono>

namespace rockcontact::dynamics {

class RunClock {
 public:
  using clock = std::chrono::steady_clock;

  // Starts the run's time.
  RunClock() : start_(clock::now()) {}

  // Calls `write` and counts its time as output.
  template <class Write>
  void output(Write&& write) {
    const clock::time_point t0 = clock::now();
    write();
    output_ += clock::now() - t0;
  }

  // s, wall, since the start and not writing files.
  double simulation_seconds() const {
    return std::chrono::duration<double>(clock::now() - start_ - output_).count();
  }

  // s, wall, writing files.
  double output_seconds() const { return std::chrono::duration<double>(output_).count(); }

 private:
  clock::time_point start_;
  clock::duration output_{};
};

}  // namespace rockcontact::dynamics
