#include "rockcontact/kernel/2d/potential.hpp"

#include "rockcontact/kernel/2d/demarcation.hpp"
#include "rockcontact/kernel/2d/detail/potential_impl.hpp"

namespace rockcontact::kernel {

double exit_distance(const ConvexPolygon& polygon, const Point2& p) {
  const detail::PointT<double> q{p.x, p.y};
  detail::EdgeTable<double> edges;
  detail::tabulate_edges(polygon, edges);
  detail::LinearPieces<double> f;
  detail::edge_distance_functions(polygon, edges, q, q, f);
  return f.at(0.0);
}

std::vector<double> demarcation_parameters(const ConvexPolygon& polygon, const Point2& a,
                                           const Point2& b, Demarcation mode, double small_edge) {
  const detail::PointT<double> pa{a.x, a.y}, pb{b.x, b.y};
  std::vector<double> t;
  if (mode == Demarcation::exact) {
    detail::EdgeTable<double> edges;
    detail::tabulate_edges(polygon, edges);
    detail::LinearPieces<double> f;
    detail::edge_distance_functions(polygon, edges, pa, pb, f);
    detail::envelope_breakpoints<Filtered>(f, t);
  } else {
    detail::paper_breakpoints(polygon, pa, pb, small_edge, t);
  }
  detail::normalise_parameters(t);
  return t;
}

}  // namespace rockcontact::kernel
