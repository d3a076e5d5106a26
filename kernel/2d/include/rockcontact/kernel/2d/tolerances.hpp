#pragma once
// Every tolerance of the 2D kernel, with its unit and its effect. There are few: predicates are
// exact, so no tolerance decides a combinatorial question. What remains are modelling choices.

namespace rockcontact::kernel {

// Paper demarcation (seed 000 §3.2.3): an edge shorter than this fraction of H gets a virtual
// node where the bisector rays of its two end nodes meet. The paper gives no value; 0.1 H keeps
// bisector rays from short chamfer edges from splitting the boundary into needlessly small
// pieces. Dimensionless (a fraction of H). Larger values merge more kinks into one virtual
// node, which moves the paper mode further from the exact envelope; the `exact` demarcation
// mode does not use it.
inline constexpr double default_small_edge_fraction = 0.1;

}  // namespace rockcontact::kernel
