// Embedding rockcontact in a host DEM code: one pair of blocks -> normal force and contact point.
#include <cstdio>

#include "rockcontact/contact/potential_contact.hpp"

int main() {
  using namespace rockcontact;
  const auto cp = kernel::ConvexPolygon::make("left", {{0, 0}, {1, 0}, {1, 1}, {0, 1}});
  const auto tp = kernel::ConvexPolygon::make("right", {{0.9, 0.2}, {1.9, 0.2}, {1.9, 1.2}, {0.9, 1.2}});
  contact::PotentialContactParams params = contact::default_potential_contact_params();
  params.kn = 1.0e7;  // Pa
  params.H = 1.0;     // m
  contact::PairWorkspace workspace;  // reuse across pairs: no allocation in steady state
  contact::PairResult r;
  contact::evaluate_pair<kernel::Filtered>(cp, tp, params, workspace, r);
  std::printf("status %s, IP area %.6g m^2\n", kernel::to_string(r.status).data(), r.area);
  std::printf("force on CP (%.6g, %.6g) N/m at (%.6g, %.6g) m\n", r.force.x, r.force.y,
              r.point->x, r.point->y);
  std::printf("%llu predicates, %llu exact fallbacks\n",
              static_cast<unsigned long long>(r.predicates), static_cast<unsigned long long>(r.fallbacks));
}
