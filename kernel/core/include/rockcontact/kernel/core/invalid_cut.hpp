#pragma once
// InvalidCut: bad input to block cutting, in 2D (kernel/2d/block_cutting.hpp) and in 3D
// (kernel/3d/block_cutting.hpp). subject() names what is refused in the cutting header's terms:
// "region" (the outline or a part of it), "joint_sets[1].spacing" (a field of a set,
// "joint_sets[1]" for the work bounds), an option, or "block near (2.5, 7.5)" (a block the cut
// would make); problem() says why; what() is "<subject>: <problem>".

#include <stdexcept>
#include <string>

namespace rockcontact::kernel {

class InvalidCut : public std::invalid_argument {
 public:
  InvalidCut(const std::string& subject, const std::string& problem)
      : std::invalid_argument(subject + ": " + problem), subject_(subject), problem_(problem) {}
  const std::string& subject() const noexcept { return subject_; }
  const std::string& problem() const noexcept { return problem_; }

 private:
  std::string subject_;
  std::string problem_;
};

}  // namespace rockcontact::kernel
