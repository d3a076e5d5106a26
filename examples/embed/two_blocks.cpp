// Embedding rockcontact in a host code: one pair of blocks -> normal force and contact point,
// through the one-header pair API (plain arrays, a reusable evaluator).
#include <cstdio>

#include "rockcontact/contact/embed/pair_contact.hpp"

int main() {
  const double square[] = {0, 0, 1, 0, 1, 1, 0, 1};  // x0, y0, x1, y1, ... (m), CCW
  rockcontact::PairContactParams params = rockcontact::default_pair_contact_params();
  params.kn = 1.0e7;  // Pa
  params.H = 1.0;     // m
  rockcontact::PairEvaluator contact(params);  // reuse across pairs: no allocation in steady state
  const rockcontact::PairContact c = contact.evaluate(square, {0.0, 0.0, 0.0},   // a at the origin
                                                      square, {0.9, 0.2, 0.0});  // b moved by (0.9, 0.2)
  const char* status[] = {"separate", "touch", "overlap"};
  std::printf("status %s, IP area %.6g m^2, penetration %.6g m\n", status[static_cast<int>(c.status)],
              c.area, c.penetration);
  std::printf("force on a (%.6g, %.6g) N/m at (%.6g, %.6g) m\n", c.force[0], c.force[1], c.point[0],
              c.point[1]);
  std::printf("%llu predicates, %llu exact fallbacks\n", static_cast<unsigned long long>(c.predicates),
              static_cast<unsigned long long>(c.fallbacks));
}
